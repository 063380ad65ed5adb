// ---- Lights (MODELS.md "Lights"), set by the application
struct FacetLight {
    position: vec4<f32>,     // xyz: position (point, spot), or the direction the light travels (directional)
                             // w: type, {{point}} point, {{directional}} directional, {{spot}} spot
    color: vec4<f32>,        // rgb: colour C; a: spot exponent
    spot: vec4<f32>,         // xyz: unit cone axis s; w: cos(cutoff)
    attenuation: vec4<f32>,  // xyz: c1, c2, c3; w: law, {{no_attenuation}} none, {{inverse_square}} inverse square, {{polynomial}} polynomial, {{inverse_square_range}} inverse square within range x
};
{{declarations}}

// m_e as it leaves the surface of normal n towards v: {{emitted_doc}}
fn facet_emitted(n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    return {{emitted}};
}

// MODELS.md: L = m_a ⊗ A + Σ att(d) · spot · C ⊗ (k_d ⊗ ρ_d + k_s ⊗ ρ_s) + m_e
// facet_visibility(p, l, d, i): how much of light i reaches p along l over distance d
// (1 unlit by shadows, 0 in shadow), defined by the code this is assembled with.
fn facet_shade(p: vec3<f32>, n: vec3<f32>, v: vec3<f32>, surface_tangent: vec3<f32>) -> vec3<f32> {
    var t = surface_tangent;
{{mapping}}    var radiance = material_ambient * facet_scene.ambient.rgb + facet_emitted({{emitted_normal}}, v);
    for (var i: i32 = 0; i < {{count}}; i++) {
        let light = facet_light(i);
        var l: vec3<f32>;
        var d: f32 = 1e30;  // directional lights have no distance
        var factor: f32 = 1.0;
        if (light.position.w == {{directional}}.0) {
            l = -normalize(light.position.xyz);
        } else {
            let to_light = light.position.xyz - p;
            d = length(to_light);
            l = to_light / d;
            if (light.attenuation.w == {{inverse_square}}.0) {
                factor = attenuation_inverse_square(d);
            } else if (light.attenuation.w == {{polynomial}}.0) {
                factor = attenuation_polynomial(d, light.attenuation.x, light.attenuation.y, light.attenuation.z);
            } else if (light.attenuation.w == {{inverse_square_range}}.0) {
                factor = attenuation_inverse_square_range(d, light.attenuation.x);
            }
            if (light.position.w == {{spot}}.0) {
                factor *= spot_cone(-dot(l, light.spot.xyz), light.spot.w, light.color.a);
            }
        }
        // Below the horizon reflectance() is 0: skip the visibility query there. The surface's
        // own normal n says which lights are above it; the lobes read ns.
        if (factor > 0.0 && dot(n, l) > 0.0) {
            radiance += factor * facet_visibility(p, l, d, i) * light.color.rgb * facet_reflect(ns, l, v, t{{coat_arg}});
        }
    }
    return radiance;
}
