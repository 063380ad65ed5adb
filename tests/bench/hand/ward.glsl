// Ward, αx = 0.1, αy = 0.3: ρ = (n·l) / (4 αx αy √((n·l)(n·v))) · exp(−((h·t/αx)² + (h·b/αy)²) / (n·h)²).
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return vec3(0.0);
    vec3 h = (l + v) * inversesqrt(max(dot(l + v, l + v), 1e-8));
    float x = dot(h, t) * 10.0, y = dot(h, cross(n, t)) * (1.0 / 0.3), c = dot(n, h);
    return vec3(NoL * inversesqrt(NoL * NoV) * (1.0 / 0.12) * exp(-(x * x + y * y) / (c * c)));
}
