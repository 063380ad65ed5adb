// Phong, n = 32: ρ = [r·v]^n, r·v = 2(n·l)(n·v) − l·v.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    return (float3)(pow(max(2.0 * NoL * NoV - dot(l, v), 0.0), 32.0));
}
