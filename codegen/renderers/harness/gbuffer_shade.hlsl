
// ---- G-buffer shading pass in HLSL (docs/architecture.md, "The G-buffer"; the vulkan-hlsl
// renderer): facet's GL ray caster has cast the scene once into seven RGBA32F images; this
// main reads them at its pixel and shades, as the ray caster's own main does after its hit,
// line for line as templates/glsl/gbuffer_shade.glsl. Texel (x, y) has y = 0 the bottom row.
// Images: 0 position (w: 1 shaded in this pass, 0 drawn black, -1 background), 1 normal,
// 2 view direction v, 3 the uv tangent frame (xyz, w = ±1), 4 uv sets 0 (xy) and 1 (zw),
// 5 the vertex colour (RGBA), 6 the lights' visibility, a 2D array: light i's bit is bit i mod
// {{bits}} of channel (i / {{bits}}) mod 4 of layer i / {{layer_lights}} (1 lit, 0 in shadow).
// Vulkan: set 1, bindings 0-6 (register space1), as the glsl450 pass; set 0 holds the FacetScene cbuffer
// (binding 0) and the material's images (1, 2, …), set 2 the lights. Each image is read with
// Load only, so a combined image sampler descriptor serves as well as a sampled image.
Texture2D<float4> facet_gbuffer_position : register(t0, space1);    // image 0
Texture2D<float4> facet_gbuffer_normal : register(t1, space1);      // image 1
Texture2D<float4> facet_gbuffer_view : register(t2, space1);        // image 2
Texture2D<float4> facet_gbuffer_uv_tangent : register(t3, space1);  // image 3
Texture2D<float4> facet_gbuffer_uv : register(t4, space1);          // image 4
Texture2D<float4> facet_gbuffer_color0 : register(t5, space1);      // image 5
Texture2DArray<float4> facet_gbuffer_visibility : register(t6, space1);  // image 6

// This pixel's texel of the G-buffer.
static int2 facet_gbuffer_texel;

float4 main(float4 facet_frag_coord : SV_Position) : SV_Target
{
    // SV_Position has y down: the G-buffer's row is counted from the bottom.
    uint width, height;
    facet_gbuffer_position.GetDimensions(width, height);
    facet_gbuffer_texel = int2(int(facet_frag_coord.x), int(height) - 1 - int(facet_frag_coord.y));
    int3 texel = int3(facet_gbuffer_texel, 0);
    float4 position = facet_gbuffer_position.Load(texel);
    if (position.w < 0.0) return float4(0.0, 0.0, 0.0, 0.0);
    if (position.w == 0.0) return float4(0.0, 0.0, 0.0, 1.0);
    float3 p = position.xyz;
    float3 n = facet_gbuffer_normal.Load(texel).xyz;
    float3 v = facet_gbuffer_view.Load(texel).xyz;
    float4 uvs = facet_gbuffer_uv.Load(texel);
    float4 frame = facet_gbuffer_uv_tangent.Load(texel);
{{sample}}    return float4(facet_shade(p, n, v, facet_tangent(n)), 1.0);
}

// Light `light`'s visibility at this pixel, as the ray caster's shadow ray found it: its
// bit of image 6.
float facet_visibility(float3 p, float3 l, float d, int light)
{
    float4 word = facet_gbuffer_visibility.Load(int4(facet_gbuffer_texel, light / {{layer_lights}}, 0));
    int bits = int(word[(light / {{bits}}) % 4]);
    return float((bits >> (light % {{bits}})) & 1);
}
