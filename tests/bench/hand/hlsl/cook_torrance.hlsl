// Cook–Torrance, m = 0.3, V-cavity G, exact Fresnel η = 1.5: ρ = π D G F / (4 n·v), π cancelled.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float3 h = (l + v) * rsqrt(max(dot(l + v, l + v), 1e-8));
    float c = min(dot(n, h), 1.0), VoH = max(dot(v, h), 0.0);
    float c2 = c * c;
    float tan2 = max((1.0 - c) * (1.0 + c), 0.0) / c2;
    float G = min(1.0, 2.0 * c * min(NoV, NoL) / VoH);
    // Fresnel: g = √(η² + c² − 1) (η² − 1 = 1.25 > 0: never total reflection)
    float g = sqrt(1.25 + VoH * VoH);
    float a = (g - VoH) / (g + VoH);
    float b = (VoH * (g + VoH) - 1.0) / (VoH * (g - VoH) + 1.0);
    float F = 0.5 * a * a * (1.0 + b * b);
    return (float3)(exp(tan2 * (-1.0 / 0.09)) * G * F / max(0.36 * c2 * c2 * NoV, 1e-30));
}
