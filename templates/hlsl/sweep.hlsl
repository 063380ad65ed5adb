
// ---- facet's robustness sweep: each pixel centre is one direction set of the
// grid (targets/sweep_grid.h); the output is the raw reflectance, NaN and Inf included.
// SV_Position's y runs down the image (Direct3D's and Vulkan's order): row 0 of the
// framebuffer is st.y = 0.5 / height, as the GLSL sweep's bottom row is.
cbuffer FacetSweep : register(b0)
{
    float2 facet_resolution;
};

float4 main(float4 facet_frag_coord : SV_Position) : SV_Target
{
    float2 st = facet_frag_coord.xy / facet_resolution;
    float3 n = float3(sweep_n_x(st.x, st.y), sweep_n_y(st.x, st.y), sweep_n_z(st.x, st.y));
    float3 l = float3(sweep_l_x(st.x, st.y), sweep_l_y(st.x, st.y), sweep_l_z(st.x, st.y));
    float3 v = float3(sweep_v_x(st.x, st.y), sweep_v_y(st.x, st.y), sweep_v_z(st.x, st.y));
    return float4(facet_reflect(n, l, v, facet_tangent(n){{coat_arg}}), 1.0);
}
