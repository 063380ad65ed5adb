// Phong, n = 32: ρ = [r·v]^n, r·v = 2(n·l)(n·v) − l·v.
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    return vec3(pow(max(2.0 * NoL * NoV - dot(l, v), 0.0), 32.0));
}
