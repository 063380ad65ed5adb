// GGX, α = 0.2, separable Smith G, Schlick F (f0 = 0.04): ρ = π D G F / (4 n·v) with
// D = α²/(π d²), d = (1 − (n·h)²) + α²(n·h)², G1(x) = 2x/(x + √(α² + (1−α²)x²)):
// π and the 2·2/4 cancel, and n·v too: ρ = α² F (n·l) / (d² (n·l + s_l)(n·v + s_v)).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = min(dot(n, h), 1.0);
    float d = (1.0 - c) * (1.0 + c) + 0.04 * c * c;
    float sl = sqrt(0.04 + 0.96 * NoL * NoL), sv = sqrt(0.04 + 0.96 * NoV * NoV);
    float F = 0.04 + 0.96 * pow(max(1.0 - dot(v, h), 0.0), 5.0);
    return (float3)(0.04 * F * NoL / max(d * d * (NoL + sl) * (NoV + sv), 1e-30));
}
