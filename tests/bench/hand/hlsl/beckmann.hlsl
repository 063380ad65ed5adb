// Beckmann, m = 0.3, G = F = 1: ρ = π D / (4 n·v), D = exp(−tan²θ_h/m²)/(π m² cos⁴θ_h);
// π cancels: ρ = exp(−tan²θ_h/m²) / (4 m² cos⁴θ_h n·v).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = min(dot(n, h), 1.0);
    float c2 = c * c;
    float tan2 = max((1.0 - c) * (1.0 + c), 0.0) / c2;
    return (float3)(exp(tan2 * (-1.0 / 0.09)) / max(0.36 * c2 * c2 * NoV, 1e-30));
}
