
// ---- G-buffer shading pass (docs/architecture.md, "The G-buffer"): facet's GL ray
// caster has cast the scene once into seven RGBA32F images; this main reads them at its
// pixel and shades, as the ray caster's own main does after its hit. Texel (x, y) has
// y = 0 the bottom row. Images: 0 position (w: 1 shaded in this pass, 0 drawn black,
// -1 background), 1 normal, 2 view direction v, 3 the uv tangent frame (xyz, w = ±1),
// 4 uv sets 0 (xy) and 1 (zw), 5 the vertex colour (RGBA, white off meshes without one),
// 6 the lights' visibility, a 2D array: light i's bit is bit i mod {{bits}} of channel
// (i / {{bits}}) mod 4 of layer i / {{layer_lights}} (1 lit, 0 in shadow), each channel an
// integer below 2^{{bits}}, exact in float32.
{{declarations}}
// This pixel's texel of the G-buffer.
ivec2 facet_gbuffer_texel;

void main()
{
    facet_gbuffer_texel = {{texel}};
    vec4 position = texelFetch(facet_gbuffer_position, facet_gbuffer_texel, 0);
    if (position.w < 0.0) {
        facet_color = vec4(0.0);
        return;
    }
    if (position.w == 0.0) {
        facet_color = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(facet_gbuffer_normal, facet_gbuffer_texel, 0).xyz;
    vec3 v = texelFetch(facet_gbuffer_view, facet_gbuffer_texel, 0).xyz;
    vec4 uvs = texelFetch(facet_gbuffer_uv, facet_gbuffer_texel, 0);
    vec4 frame = texelFetch(facet_gbuffer_uv_tangent, facet_gbuffer_texel, 0);
{{sample}}    facet_color = vec4(facet_shade(p, n, v, facet_tangent(n)), 1.0);
}

// Light `light`'s visibility at this pixel, as the ray caster's shadow ray found it: its
// bit of image 6.
float facet_visibility(vec3 p, vec3 l, float d, int light)
{
    vec4 word = texelFetch(facet_gbuffer_visibility, ivec3(facet_gbuffer_texel, light / {{layer_lights}}), 0);
    int bits = int(word[(light / {{bits}}) % 4]);
    return float((bits >> (light % {{bits}})) & 1);
}
