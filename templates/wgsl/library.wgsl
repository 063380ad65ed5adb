const PI: f32 = 3.14159265358979;

// ---- Material constants
{{constants}}
{{textures}}// ---- Terms (one function per term of the model catalog)

{{functions}}
// MODELS.md tangent rule: t = normalize(axis × n), or x̂ × n where |axis × n| < ε.
fn facet_tangent(n: vec3<f32>) -> vec3<f32> {
    var t = cross(tangent_axis, n);
    if (length(t) < 1e-4) {
        t = cross(vec3<f32>(1.0, 0.0, 0.0), n);
    }
    return normalize(t);
}

// Radiance reflected towards v from a light of unit colour arriving from l.
// n, l, v and t are unit vectors, t ⟂ n{{coat_doc}}.
fn facet_reflect(n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, t: vec3<f32>{{coat_param}}) -> vec3<f32> {
{{inputs}}    return reflectance({{arguments}});
}
