// glTF's BRDF (Appendix B) at the lobe's defaults: a dielectric (metallic 0) of base colour
// 0.8, roughness 0.5 (α = 0.25), ior 1.5 and specular 1 (f0 = 0.04, f90 = 1): ρ = F S +
// (1 − F) 0.8 (n·l), S = π D V (n·l) with D = α²/(π d²), d = (1 − (n·h)²) + α²(n·h)² and
// the height-correlated V = 1/(2((n·v) s_l + (n·l) s_v)), s_x = √(α² + (1−α²)x²): π cancels,
// S = α²/2 · (n·l) / (d² ((n·v) s_l + (n·l) s_v)); F = 0.04 + 0.96 (1 − v·h)^5, grey.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = min(dot(n, h), 1.0);
    float d = (1.0 - c) * (1.0 + c) + 0.0625 * c * c;
    float sl = sqrt(0.0625 + 0.9375 * NoL * NoL), sv = sqrt(0.0625 + 0.9375 * NoV * NoV);
    float S = 0.03125 * NoL / max(d * d * (NoV * sl + NoL * sv), 1e-30);
    float F = 0.04 + 0.96 * pow(max(1.0 - dot(v, h), 0.0), 5.0);
    return (float3)(F * S + (1.0 - F) * 0.8 * NoL);
}
