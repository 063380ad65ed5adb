// Gaussian, m = 50: ρ = exp(−m θ_h²), θ_h = acos(n·h) as atan(√(1 − c²), c).
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    vec3 h = (l + v) * inversesqrt(max(dot(l + v, l + v), 1e-8));
    float c = clamp(dot(n, h), 0.0, 1.0);
    float theta = atan(sqrt(max(1.0 - c * c, 0.0)), c);
    return vec3(exp(-50.0 * theta * theta));
}
