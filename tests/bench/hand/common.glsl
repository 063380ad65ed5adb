// The hand-minimized BRDFs (tests/bench/README.md): what the cost frame reads
// besides facet_reflect(). Every hand file below keeps the guards facet's
// generated code keeps (the horizon rule, MODELS.md's ε tests, pow and sqrt
// arguments that rounding can make negative clamped at 0, denominators that can
// underflow floored at 1e-30, n·h ≤ 1, |l + v| ≥ ε for the half vector) and the
// same cancellation-free forms ((1 − c)(1 + c) for 1 − c²), and is otherwise
// written as tightly as the formula allows: constants folded by hand, π and
// factors of 2 cancelled, grey colours as scalars, shared subexpressions.
const vec3 material_ambient = vec3(0.0);
const vec3 material_emission = vec3(0.0);

// MODELS.md tangent rule for the default axis (0, 1, 0).
vec3 facet_tangent(vec3 n)
{
    vec3 t = cross(vec3(0.0, 1.0, 0.0), n);
    if (length(t) < 1e-4) t = cross(vec3(1.0, 0.0, 0.0), n);
    return normalize(t);
}
