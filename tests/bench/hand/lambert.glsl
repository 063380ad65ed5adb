// Lambert: ρ = n·l.
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l);
    return vec3(min(NoL, dot(n, v)) > 0.0 ? NoL : 0.0);
}
