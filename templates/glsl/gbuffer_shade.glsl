
// ---- G-buffer shading pass (docs/architecture.md, "The G-buffer"): facet's GL ray
// caster has cast the scene once into seven RGBA32F images; this main reads them at its
// pixel and shades, as the ray caster's own main does after its hit. Texel (x, y) has
// y = 0 the bottom row. Images: 0 position (w: 1 shaded in this pass, 0 drawn black,
// -1 background), 1 normal, 2 view direction v, 3 the uv tangent frame (xyz, w = ±1),
// 4 uv sets 0 (xy) and 1 (zw), 5 and 6 the visibility of lights 0-3 and 4-7.
{{declarations}}
// This pixel's visibility of lights 0-3 and 4-7, read from images 5 and 6.
vec4 facet_visible_low;
vec4 facet_visible_high;

void main()
{
    ivec2 texel = {{texel}};
    vec4 position = texelFetch(facet_gbuffer_position, texel, 0);
    if (position.w < 0.0) {
        facet_color = vec4(0.0);
        return;
    }
    if (position.w == 0.0) {
        facet_color = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    facet_visible_low = texelFetch(facet_gbuffer_visibility_low, texel, 0);
    facet_visible_high = texelFetch(facet_gbuffer_visibility_high, texel, 0);
    vec3 p = position.xyz;
    vec3 n = texelFetch(facet_gbuffer_normal, texel, 0).xyz;
    vec3 v = texelFetch(facet_gbuffer_view, texel, 0).xyz;
    vec4 uvs = texelFetch(facet_gbuffer_uv, texel, 0);
    vec4 frame = texelFetch(facet_gbuffer_uv_tangent, texel, 0);
{{sample}}    facet_color = vec4(facet_shade(p, n, v, facet_tangent(n)), 1.0);
}

// Light `light`'s visibility at this pixel, as the ray caster's shadow ray found it.
float facet_visibility(vec3 p, vec3 l, float d, int light)
{
    vec4 four = light < 4 ? facet_visible_low : facet_visible_high;
    int k = light < 4 ? light : light - 4;
    return k == 0 ? four.x : (k == 1 ? four.y : (k == 2 ? four.z : four.w));
}
