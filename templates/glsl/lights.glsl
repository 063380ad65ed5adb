// ---- Lights (MODELS.md "Lights"), set by the application
struct FacetLight {
    vec4 position;     // xyz: position (point, spot), or the direction the light travels (directional)
                       // w: type, {{point}} point, {{directional}} directional, {{spot}} spot
    vec4 color;        // rgb: colour C; a: spot exponent
    vec4 spot;         // xyz: unit cone axis s; w: cos(cutoff)
    vec4 attenuation;  // xyz: c1, c2, c3; w: law, {{no_attenuation}} none, {{inverse_square}} inverse square, {{polynomial}} polynomial, {{inverse_square_range}} inverse square within range x
};
{{declarations}}

// How much of light `light` (the i of facet_light(i)) reaches p along l over
// distance d: 1 unlit by shadows, 0 in shadow. Defined by the code that includes
// this shader: the standalone main's returns 1 (an engine's shadow lookup goes
// there), facet's GL ray caster casts a shadow ray and ignores the index, and the
// G-buffer shading pass (glsl/gbuffer_shade.glsl) reads the light's visibility
// from the G-buffer by its index.
float facet_visibility(vec3 p, vec3 l, float d, int light);

// m_e as it leaves the surface of normal n towards v: {{emitted_doc}}
vec3 facet_emitted(vec3 n, vec3 v)
{
    return {{emitted}};
}

// MODELS.md: L = m_a ⊗ A + Σ att(d) · spot · C ⊗ (k_d ⊗ ρ_d + k_s ⊗ ρ_s) + m_e
vec3 facet_shade(vec3 p, vec3 n, vec3 v, vec3 t)
{
{{mapping}}    vec3 radiance = material_ambient * facet_ambient.rgb + facet_emitted({{emitted_normal}}, v);
    for (int i = 0; i < {{count}}; ++i) {
        FacetLight light = facet_light(i);
        vec3 l;
        float d = 1e30;  // directional lights have no distance
        float factor = 1.0;
        if (light.position.w == {{directional}}.0) {
            l = -normalize(light.position.xyz);
        } else {
            vec3 to_light = light.position.xyz - p;
            d = length(to_light);
            l = to_light / d;
            if (light.attenuation.w == {{inverse_square}}.0) {
                factor = attenuation_inverse_square(d);
            } else if (light.attenuation.w == {{polynomial}}.0) {
                factor = attenuation_polynomial(d, light.attenuation.x, light.attenuation.y, light.attenuation.z);
            } else if (light.attenuation.w == {{inverse_square_range}}.0) {
                factor = attenuation_inverse_square_range(d, light.attenuation.x);
            }
            if (light.position.w == {{spot}}.0) factor *= spot_cone(-dot(l, light.spot.xyz), light.spot.w, light.color.a);
        }
        // Below the horizon reflectance() is 0: skip the visibility query there. The surface's
        // own normal n says which lights are above it; the lobes read ns.
        if (factor > 0.0 && dot(n, l) > 0.0)
            radiance += factor * facet_visibility(p, l, d, i) * light.color.rgb * facet_reflect(ns, l, v, t{{coat_arg}});
    }
    return radiance;
}
