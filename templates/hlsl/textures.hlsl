// ---- Textures (docs/textures.md), glTF's convention on every target: (u, v) = (0, 0)
// is the picture's top-left corner, texel (i, j) covers [i, i+1)/W × [j, j+1)/H (rows
// uploaded from the top, so Load's j is the file's row j), wrapping acts on texel
// indices, sRGB is decoded per texel before the bilinear blend. The images hold the
// file's values (RGBA32F) and are read with Load only: no sampler, no mipmaps, the
// same numbers on every GPU.

// A texel index wrapped into [0, size): 0 repeat, 1 clamp, 2 mirror (glTF's MIRRORED_REPEAT).
int facet_wrap(int i, int size, int mode)
{
    if (mode == 1) return clamp(i, 0, size - 1);
    int period = mode == 2 ? 2 * size : size;
    int m = i - period * int(floor(float(i) / float(period)));  // % keeps the sign of i: not a modulo below 0
    return m < size ? m : period - 1 - m;
}

// IEC 61966-2-1: c ≤ 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4; alpha stays linear.
float facet_srgb_channel(float c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

float4 facet_srgb_decode(float4 c)
{
    return float4(facet_srgb_channel(c.r), facet_srgb_channel(c.g), facet_srgb_channel(c.b), c.a);
}

float4 facet_texel(Texture2D<float4> image, int2 size, int i, int j, int2 wrap, bool srgb)
{
    float4 c = image.Load(int3(facet_wrap(i, size.x, wrap.x), facet_wrap(j, size.y, wrap.y), 0));
    return srgb ? facet_srgb_decode(c) : c;
}

// The filtered value at (u, v): nearest reads texel (⌊u·W⌋, ⌊v·H⌋); bilinear blends the
// four texel centres around (u·W − ½, v·H − ½).
float4 facet_texture(Texture2D<float4> image, float2 uv, int2 wrap, bool bilinear, bool srgb)
{
    uint width, height;
    image.GetDimensions(width, height);
    int2 size = int2(int(width), int(height));
    float2 x = uv * float2(size);
    if (!bilinear) return facet_texel(image, size, int(floor(x.x)), int(floor(x.y)), wrap, srgb);
    x -= 0.5;
    float2 f = floor(x);
    float2 w = x - f;
    int i = int(f.x), j = int(f.y);
    float4 c00 = facet_texel(image, size, i, j, wrap, srgb);
    float4 c10 = facet_texel(image, size, i + 1, j, wrap, srgb);
    float4 c01 = facet_texel(image, size, i, j + 1, wrap, srgb);
    float4 c11 = facet_texel(image, size, i + 1, j + 1, wrap, srgb);
    return lerp(lerp(c00, c10, w.x), lerp(c01, c11, w.x), w.y);
}

{{uniforms}}
// The parameters that come from images, at the shading point: facet_sample_textures sets them.
{{globals}}
// Texture coordinates sets 0 and 1 (glTF's TEXCOORD_0/1: v down the picture){{color_doc}} → each
// textured parameter: clamp({{offset}}factor ⊗ channel(texture(KHR_texture_transform(uv))){{vc}}, its range).
void facet_sample_textures({{params}})
{
{{samples}}}
