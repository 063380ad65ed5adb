// Heidrich–Seidel, n = 32: ρ = [√(1−(l·t)²)√(1−(v·t)²) − (l·t)(v·t)]^n.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float LoT = dot(l, t), VoT = dot(v, t);
    float x = sqrt(max(1.0 - LoT * LoT, 0.0) * max(1.0 - VoT * VoT, 0.0)) - LoT * VoT;
    return (float3)(pow(max(x, 0.0), 32.0));
}
