// Minnaert velvet, k = 0.5: ρ = (n·l)^(k+1) · (1 − n·v)^(1−k).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    return (float3)(pow(max(NoL, 0.0), 1.5) * pow(max(1.0 - NoV, 0.0), 0.5));
}
