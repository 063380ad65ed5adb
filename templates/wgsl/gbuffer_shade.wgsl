
// ---- G-buffer shading pass (docs/architecture.md, "The G-buffer"), the wgpu renderer's:
// facet's GL ray caster has cast the scene once into seven rgba32float images (@group(1));
// this pass reads them at its pixel and shades, as the ray caster's own main does after its
// hit. Texel (x, y) has y = 0 the bottom row; this framebuffer has y down, so pixel (x, y)
// reads texel (x, height − 1 − y) and the image comes back in facet's order (top row
// first). Images: 0 position (w: 1 shaded in this pass, 0 drawn black, −1 background),
// 1 normal, 2 view direction v, 3 the uv tangent frame (xyz, w = ±1), 4 uv sets 0 (xy)
// and 1 (zw), 5 the vertex colour (RGBA), 6 the lights' visibility, a 2D array: light i's bit
// is bit i mod {{bits}} of channel (i / {{bits}}) mod 4 of layer i / {{layer_lights}} (1 lit, 0 in
// shadow), each channel an integer below 2^{{bits}}, exact in f32.
@group(1) @binding(0) var facet_gbuffer_position: texture_2d<f32>;
@group(1) @binding(1) var facet_gbuffer_normal: texture_2d<f32>;
@group(1) @binding(2) var facet_gbuffer_view: texture_2d<f32>;
@group(1) @binding(3) var facet_gbuffer_uv_tangent: texture_2d<f32>;
@group(1) @binding(4) var facet_gbuffer_uv: texture_2d<f32>;
@group(1) @binding(5) var facet_gbuffer_color0: texture_2d<f32>;
@group(1) @binding(6) var facet_gbuffer_visibility: texture_2d_array<f32>;

// This pixel's texel of the G-buffer.
var<private> facet_gbuffer_texel: vec2<i32>;

// One triangle over the whole framebuffer.
@vertex
fn facet_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn facet_gbuffer_shade(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let size = vec2<i32>(textureDimensions(facet_gbuffer_position, 0));
    facet_gbuffer_texel = vec2<i32>(i32(pixel.x), size.y - 1 - i32(pixel.y));
    let texel = facet_gbuffer_texel;
    let position = textureLoad(facet_gbuffer_position, texel, 0);
    if (position.w < 0.0) {
        return vec4<f32>(0.0);
    }
    if (position.w == 0.0) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let p = position.xyz;
    let n = textureLoad(facet_gbuffer_normal, texel, 0).xyz;
    let v = textureLoad(facet_gbuffer_view, texel, 0).xyz;
    let uv = textureLoad(facet_gbuffer_uv, texel, 0);
    let frame = textureLoad(facet_gbuffer_uv_tangent, texel, 0);
{{sample}}    return vec4<f32>(facet_shade(p, n, v, facet_tangent(n)), 1.0);
}

// Light `light`'s visibility at this pixel, as the ray caster's shadow ray found it: its
// bit of image 6.
fn facet_visibility(p: vec3<f32>, l: vec3<f32>, d: f32, light: i32) -> f32 {
    let word = textureLoad(facet_gbuffer_visibility, facet_gbuffer_texel, light / {{layer_lights}}, 0);
    let bits = i32(word[(light / {{bits}}) % 4]);
    return f32((bits >> u32(light % {{bits}})) & 1);
}
