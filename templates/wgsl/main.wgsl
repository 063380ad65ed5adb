
// ---- Standalone entry point: world-space position and normal from the vertex shader
struct FacetFragment {
{{inputs}}};

@fragment
fn main(fragment: FacetFragment) -> @location(0) vec4<f32> {
    let n = normalize(fragment.normal);
    let v = normalize(facet_scene.camera_position.xyz - fragment.position);
    let t = facet_tangent(n);
{{sample}}    return vec4<f32>(facet_shade(fragment.position, n, v, t), 1.0);
}

// This standalone shader casts no shadows; an engine puts its shadow lookup here.
fn facet_visibility(p: vec3<f32>, l: vec3<f32>, d: f32, light: i32) -> f32 {
    return 1.0;
}
