// Minnaert, k = 0.8: ρ = (n·l)^k · max(n·v, ε)^(k−1).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    return (float3)(pow(max(NoL, 0.0), 0.8) * pow(max(NoV, 1e-4), -0.2));
}
