
// ---- Standalone entry point, a Shader Model 5 pixel shader: world-space position and normal
// from the vertex shader. Direct3D matches the inputs by semantic; for Vulkan each is at the
// glsl450 shader's location (dxc -spirv defines __spirv__; glslangValidator -D: add -DFACET_SPIRV).
#if defined(__spirv__) || defined(FACET_SPIRV)
#define FACET_LOCATION(n) [[vk::location(n)]]
#else
#define FACET_LOCATION(n)
#endif
float4 main(FACET_LOCATION(0) float3 facet_position : TEXCOORD0,  // world space
            FACET_LOCATION(1) float3 facet_normal : TEXCOORD1     // world space
#ifdef FACET_VERTEX_TANGENT
            , FACET_LOCATION(2) float3 facet_vertex_tangent : TEXCOORD2
#endif
{{inputs}}            ) : SV_Target
{
    float3 n = normalize(facet_normal);
    float3 v = normalize(facet_camera_position.xyz - facet_position);
#ifdef FACET_VERTEX_TANGENT
    float3 t = normalize(facet_vertex_tangent - n * dot(n, facet_vertex_tangent));
#else
    float3 t = facet_tangent(n);
#endif
{{sample}}    return float4(facet_shade(facet_position, n, v, t), 1.0);
}

// This standalone shader casts no shadows; an engine puts its shadow lookup here.
float facet_visibility(float3 p, float3 l, float d, int light)
{
    return 1.0;
}
