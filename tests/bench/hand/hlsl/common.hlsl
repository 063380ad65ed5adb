// HLSL: the hand versions of ../*.glsl, the same formulas written in HLSL (float3, rsqrt,
// atan2), for the HLSL path of facet_hand_bench (facet's --target hlsl in the cost frame
// codegen/renderers/harness/cost.hlsl).
//
// The hand-minimized BRDFs (tests/bench/README.md): what the cost frame reads
// besides facet_reflect(). Every hand file below keeps the guards facet's
// generated code keeps (the horizon rule, MODELS.md's ε tests, pow and sqrt
// arguments that rounding can make negative clamped at 0, denominators that can
// underflow floored at 1e-30, n·h ≤ 1, |l + v| ≥ ε for the half vector) and the
// same cancellation-free forms ((1 − c)(1 + c) for 1 − c²), and is otherwise
// written as tightly as the formula allows: constants folded by hand, π and
// factors of 2 cancelled, grey colours as scalars, shared subexpressions.
static const float3 material_ambient = float3(0.0, 0.0, 0.0);
static const float3 material_emission = float3(0.0, 0.0, 0.0);

// MODELS.md tangent rule for the default axis (0, 1, 0).
float3 facet_tangent(float3 n)
{
    float3 t = cross(float3(0.0, 1.0, 0.0), n);
    if (length(t) < 1e-4) t = cross(float3(1.0, 0.0, 0.0), n);
    return normalize(t);
}
