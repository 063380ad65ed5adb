
// ---- facet's cost frame in HLSL (analysis/cost.h): cost_raycast.glsl and cost.glsl as a
// pixel shader, for the HLSL path's SPIR-V count (glslangValidator -D -V, spirv-opt -O).
// The built-in scene "single": one ray per pixel centre against its sphere, shaded by its
// one point light: no attenuation, no shadow test, no light loop.
cbuffer FacetCostFrame : register(b0)
{
    float2 facet_resolution;
    float3 facet_camera_position;
    float3 facet_camera_forward;
    float3 facet_camera_right;
    float3 facet_camera_up;
    float2 facet_camera_tan;      // tan(fov/2) · (aspect, 1)
    float4 facet_sphere;          // centre, radius
    float3 facet_light_position;
    float3 facet_light_color;
    float3 facet_ambient;
};

// The camera ray through this pixel centre (SV_Position: y down, so flipped to GL's
// gl_FragCoord) and where it meets the sphere, with the normal there; false where it misses.
bool facet_camera_hit(float2 frag, out float3 dir, out float3 p, out float3 n)
{
    float2 ndc = 2.0 * float2(frag.x, facet_resolution.y - frag.y) / facet_resolution - 1.0;
    dir = normalize(facet_camera_forward + facet_camera_right * (ndc.x * facet_camera_tan.x)
                    + facet_camera_up * (ndc.y * facet_camera_tan.y));
    p = float3(0.0, 0.0, 0.0);
    n = float3(0.0, 0.0, 0.0);
    float3 oc = facet_camera_position - facet_sphere.xyz;
    float b = dot(oc, dir);
    float c = dot(oc, oc) - facet_sphere.w * facet_sphere.w;
    float disc = b * b - c;
    if (disc < 0.0 || b > 0.0) return false;
    // The camera is outside the sphere, looking at it (b < 0): the near root
    // c / (√disc − b) has no cancellation.
    p = facet_camera_position + dir * (c / (sqrt(disc) - b));
    n = normalize(p - facet_sphere.xyz);
    return true;
}

float4 main(float4 facet_frag_coord : SV_Position) : SV_Target
{
    float3 dir, p, n;
    if (!facet_camera_hit(facet_frag_coord.xy, dir, p, n)) return float4(0.0, 0.0, 0.0, 0.0);
    float3 l = normalize(facet_light_position - p);
    float3 radiance = material_ambient * facet_ambient + material_emission
                    + facet_light_color * facet_reflect(n, l, -dir, facet_tangent(n));
    return float4(radiance, 1.0);
}
