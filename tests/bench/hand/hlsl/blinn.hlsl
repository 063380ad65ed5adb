// Blinn (Trowbridge–Reitz), c = 0.3, V-cavity G, exact Fresnel η = 1.5: ρ = D G F / (n·v),
// D = (c² / ((n·h)²(c² − 1) + 1))².
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = min(dot(n, h), 1.0), VoH = max(dot(v, h), 0.0);
    float r = 0.09 / max((1.0 - c) * (1.0 + c) + 0.09 * c * c, 1e-30);
    float G = min(1.0, 2.0 * c * min(NoV, NoL) / VoH);
    float g = sqrt(1.25 + VoH * VoH);
    float a = (g - VoH) / (g + VoH);
    float b = (VoH * (g + VoH) - 1.0) / (VoH * (g - VoH) + 1.0);
    float F = 0.5 * a * a * (1.0 + b * b);
    return (float3)(r * r * G * F / NoV);
}
