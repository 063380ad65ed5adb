// Blinn–Phong, n = 64: ρ = [n·h]^n.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    return (float3)(pow(clamp(dot(n, h), 0.0, 1.0), 64.0));
}
