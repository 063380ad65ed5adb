// Lambert: ρ = n·l.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l);
    return (float3)(min(NoL, dot(n, v)) > 0.0 ? NoL : 0.0);
}
