// Oren–Nayar, σ = 0.3, q = 0.33: ρ = (n·l)(A + B max(0, l·v − (n·l)(n·v)) / max(n·l, n·v)),
// 0 for the B term where a projection is shorter than ε: sin θ < 1e-4, i.e. cos θ ≥ √(1 − 1e-8),
// which in float is cos θ = 1.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t)
{
    float NoL = dot(n, l), NoV = dot(n, v);
    if (min(NoL, NoV) <= 0.0) return float3(0.0, 0.0, 0.0);
    float c = max(NoL, NoV);
    float s = c >= 1.0 ? 0.0 : max(dot(l, v) - NoL * NoV, 0.0) / c;
    // A = 1 − 0.5 σ²/(σ² + 0.33), B = 0.45 σ²/(σ² + 0.09) for σ² = 0.09
    return (float3)(NoL * (0.8928571428571429 + 0.225 * s));
}
