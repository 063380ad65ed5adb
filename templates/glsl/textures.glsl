// ---- Textures (docs/textures.md), glTF's convention on every target: (u, v) = (0, 0)
// is the picture's top-left corner, texel (i, j) covers [i, i+1)/W × [j, j+1)/H (rows
// uploaded from the top, so texelFetch's j is the file's row j), wrapping acts on texel
// indices, sRGB is decoded per texel before the bilinear blend. The images hold the
// file's values (RGBA32F) and are read with texelFetch only: no sampler state, no
// mipmaps, the same numbers on every GPU.

// A texel index wrapped into [0, size): 0 repeat, 1 clamp, 2 mirror (glTF's MIRRORED_REPEAT).
int facet_wrap(int i, int size, int mode)
{
    if (mode == 1) return clamp(i, 0, size - 1);
    int period = mode == 2 ? 2 * size : size;
    int m = i - period * int(floor(float(i) / float(period)));  // % is undefined below 0
    return m < size ? m : period - 1 - m;
}

// IEC 61966-2-1: c ≤ 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4; alpha stays linear.
vec4 facet_srgb_decode(vec4 c)
{
    vec3 lo = c.rgb / 12.92;
    vec3 hi = pow((c.rgb + 0.055) / 1.055, vec3(2.4));
    return vec4(mix(hi, lo, lessThanEqual(c.rgb, vec3(0.04045))), c.a);
}

vec4 facet_texel(sampler2D image, ivec2 size, int i, int j, ivec2 wrap, bool srgb)
{
    vec4 c = texelFetch(image, ivec2(facet_wrap(i, size.x, wrap.x), facet_wrap(j, size.y, wrap.y)), 0);
    return srgb ? facet_srgb_decode(c) : c;
}

// The filtered value at (u, v): nearest reads texel (⌊u·W⌋, ⌊v·H⌋); bilinear blends the
// four texel centres around (u·W − ½, v·H − ½).
vec4 facet_texture(sampler2D image, vec2 uv, ivec2 wrap, bool bilinear, bool srgb)
{
    ivec2 size = textureSize(image, 0);
    vec2 x = uv * vec2(size);
    if (!bilinear) return facet_texel(image, size, int(floor(x.x)), int(floor(x.y)), wrap, srgb);
    x -= 0.5;
    vec2 f = floor(x);
    vec2 w = x - f;
    int i = int(f.x), j = int(f.y);
    vec4 c00 = facet_texel(image, size, i, j, wrap, srgb);
    vec4 c10 = facet_texel(image, size, i + 1, j, wrap, srgb);
    vec4 c01 = facet_texel(image, size, i, j + 1, wrap, srgb);
    vec4 c11 = facet_texel(image, size, i + 1, j + 1, wrap, srgb);
    return mix(mix(c00, c10, w.x), mix(c01, c11, w.x), w.y);
}

{{uniforms}}
// The parameters that come from images, at the shading point: facet_sample_textures sets them.
{{globals}}
// Texture coordinates sets 0 and 1 (glTF's TEXCOORD_0/1: v down the picture){{color_doc}} → each
// textured parameter: clamp({{offset}}factor ⊗ channel(texture(KHR_texture_transform(uv))){{vc}}, its range).
void facet_sample_textures({{params}})
{
{{samples}}}

