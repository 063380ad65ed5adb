// Blinn–Phong, n = 64: ρ = [n·h]^n.
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    vec3 h = (l + v) * inversesqrt(max(dot(l + v, l + v), 1e-8));
    return vec3(pow(clamp(dot(n, h), 0.0, 1.0), 64.0));
}
