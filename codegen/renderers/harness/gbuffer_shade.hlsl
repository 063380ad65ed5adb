
// ---- facet's G-buffer shading pass in HLSL (the vulkan-hlsl renderer; the G-buffer
// contract, codegen/renderers/harness/raycast.glsl's G-buffer main): the GL ray caster
// wrote seven RGBA32F images, texel (x, y) with y = 0 the bottom row; this pass reads
// them at its pixel and shades as raycast.glsl's main does after the hit.
// Set 0 is the standalone shader's (the FacetScene cbuffer at binding 0, the material's
// textures at 1, 2, …); the G-buffer is set 1, bindings 0–6 (register space1).
Texture2D<float4> facet_gbuffer_position : register(t0, space1);  // p (world), w: 1 shaded, 0 black, −1 no hit
Texture2D<float4> facet_gbuffer_normal : register(t1, space1);    // the unit normal n
Texture2D<float4> facet_gbuffer_view : register(t2, space1);      // v = −(the camera ray's unit direction)
Texture2D<float4> facet_gbuffer_tangent : register(t3, space1);   // facet_uv_tangent_at(): xyz, w = ±1
Texture2D<float4> facet_gbuffer_uv : register(t4, space1);        // texture coordinates sets 0 (xy) and 1 (zw)
Texture2D<float4> facet_gbuffer_lights0 : register(t5, space1);   // lights 0–3: 1 lit, 0 in shadow
Texture2D<float4> facet_gbuffer_lights1 : register(t6, space1);   // lights 4–7

// The G-buffer texel of this pixel.
static int3 facet_pixel_texel;

float4 main(float4 facet_frag_coord : SV_Position) : SV_Target
{
    // SV_Position's y runs down the framebuffer; the G-buffer's row 0 is the bottom one.
    uint width, height;
    facet_gbuffer_position.GetDimensions(width, height);
    facet_pixel_texel = int3(int(facet_frag_coord.x), int(height) - 1 - int(facet_frag_coord.y), 0);
    float4 position = facet_gbuffer_position.Load(facet_pixel_texel);
    if (position.w < 0.0) return float4(0.0, 0.0, 0.0, 0.0);  // no hit: the background
    if (position.w == 0.0) return float4(0.0, 0.0, 0.0, 1.0);  // another pass's object
    float3 p = position.xyz;
    float3 n = facet_gbuffer_normal.Load(facet_pixel_texel).xyz;
    float3 v = facet_gbuffer_view.Load(facet_pixel_texel).xyz;
{{sample}}    return float4(facet_shade(p, n, v, facet_tangent(n)), 1.0);
}

// Light i's visibility, as the ray cast's shadow ray found it.
float facet_visibility(float3 p, float3 l, float d, int i)
{
    float4 lit = i < 4 ? facet_gbuffer_lights0.Load(facet_pixel_texel) : facet_gbuffer_lights1.Load(facet_pixel_texel);
    return lit[i & 3];
}
