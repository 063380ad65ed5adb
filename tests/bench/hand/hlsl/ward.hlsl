// Ward, αx = 0.1, αy = 0.3: ρ = (n·l) / (4 αx αy √((n·l)(n·v))) · exp(−((h·t/αx)² + (h·b/αy)²) / (n·h)²).
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float x = dot(h, t) * 10.0, y = dot(h, cross(n, t)) * (1.0 / 0.3), c = dot(n, h);
    return (float3)(NoL * rsqrt(NoL * NoV) * (1.0 / 0.12) * exp(-(x * x + y * y) / (c * c)));
}
