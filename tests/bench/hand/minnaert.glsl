// Minnaert, k = 0.8: ρ = (n·l)^k · max(n·v, ε)^(k−1).
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    return vec3(pow(max(NoL, 0.0), 0.8) * pow(max(NoV, 1e-4), -0.2));
}
