// Minnaert velvet, k = 0.5: ρ = (n·l)^(k+1) · (1 − n·v)^(1−k).
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    return vec3(pow(max(NoL, 0.0), 1.5) * pow(max(1.0 - NoV, 0.0), 0.5));
}
