#ifndef PI
#define PI 3.14159265358979
#endif

// ---- Material constants
{{constants}}
{{textures}}// ---- Terms (one function per term of the model catalog)

{{functions}}
// MODELS.md tangent rule: t = normalize(axis × n), or x̂ × n where |axis × n| < ε.
float3 facet_tangent(float3 n)
{
    float3 t = cross(tangent_axis, n);
    if (length(t) < 1e-4) t = cross(float3(1.0, 0.0, 0.0), n);
    return normalize(t);
}

// Radiance reflected towards v from a light of unit colour arriving from l.
// n, l, v and t are unit vectors, t ⟂ n{{coat_doc}}.
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t{{coat_param}})
{
{{inputs}}    return reflectance({{arguments}});
}
