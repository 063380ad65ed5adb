// ---- Textures (docs/textures.md), glTF's convention on every target: (u, v) = (0, 0)
// is the picture's top-left corner, texel (i, j) covers [i, i+1)/W × [j, j+1)/H (rows
// uploaded from the top, so textureLoad's j is the file's row j), wrapping acts on texel
// indices, sRGB is decoded per texel before the bilinear blend. The images hold the
// file's values (rgba32float, @group(0) from @binding(1)) and are read with textureLoad
// only: no sampler, no mipmaps, the same numbers on every GPU.

// A texel index wrapped into [0, size): 0 repeat, 1 clamp, 2 mirror (glTF's MIRRORED_REPEAT).
fn facet_wrap(i: i32, size: i32, mode: i32) -> i32 {
    if (mode == 1) {
        return clamp(i, 0, size - 1);
    }
    let period = select(size, 2 * size, mode == 2);
    let m = i - period * i32(floor(f32(i) / f32(period)));  // % truncates towards 0
    return select(period - 1 - m, m, m < size);
}

// IEC 61966-2-1: c ≤ 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4; alpha stays linear.
fn facet_srgb_decode(c: vec4<f32>) -> vec4<f32> {
    let lo = c.rgb / 12.92;
    let hi = pow((c.rgb + 0.055) / 1.055, vec3<f32>(2.4));
    return vec4<f32>(select(hi, lo, c.rgb <= vec3<f32>(0.04045)), c.a);
}

fn facet_texel(image: texture_2d<f32>, size: vec2<i32>, i: i32, j: i32, wrap: vec2<i32>, srgb: bool) -> vec4<f32> {
    let c = textureLoad(image, vec2<i32>(facet_wrap(i, size.x, wrap.x), facet_wrap(j, size.y, wrap.y)), 0);
    if (srgb) {
        return facet_srgb_decode(c);
    }
    return c;
}

// The filtered value at (u, v): nearest reads texel (⌊u·W⌋, ⌊v·H⌋); bilinear blends the
// four texel centres around (u·W − ½, v·H − ½).
fn facet_texture(image: texture_2d<f32>, uv: vec2<f32>, wrap: vec2<i32>, bilinear: bool, srgb: bool) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(image, 0));
    let x = uv * vec2<f32>(size);
    if (!bilinear) {
        return facet_texel(image, size, i32(floor(x.x)), i32(floor(x.y)), wrap, srgb);
    }
    let corner = x - 0.5;
    let f = floor(corner);
    let w = corner - f;
    let i = i32(f.x);
    let j = i32(f.y);
    let c00 = facet_texel(image, size, i, j, wrap, srgb);
    let c10 = facet_texel(image, size, i + 1, j, wrap, srgb);
    let c01 = facet_texel(image, size, i, j + 1, wrap, srgb);
    let c11 = facet_texel(image, size, i + 1, j + 1, wrap, srgb);
    return mix(mix(c00, c10, w.x), mix(c01, c11, w.x), w.y);
}

{{uniforms}}
// The parameters that come from images, at the shading point: facet_sample_textures sets them.
{{globals}}
// Texture coordinates sets 0 and 1 (glTF's TEXCOORD_0/1: v down the picture){{color_doc}} → each
// textured parameter: clamp({{offset}}factor ⊗ channel(texture(KHR_texture_transform(uv))){{vc}}, its range).
fn facet_sample_textures({{params}}) {
{{samples}}}
