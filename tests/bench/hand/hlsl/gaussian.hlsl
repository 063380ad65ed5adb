// Gaussian, m = 50: ρ = exp(−m θ_h²), θ_h = acos(n·h) as atan2(√(1 − c²), c).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = clamp(dot(n, h), 0.0, 1.0);
    float theta = atan2(sqrt(max(1.0 - c * c, 0.0)), c);
    return (float3)(exp(-50.0 * theta * theta));
}
