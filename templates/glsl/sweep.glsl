
// ---- facet's robustness sweep: each pixel centre is one direction set of the
// grid (targets/sweep_grid.h); the output is the raw reflectance, NaN and Inf included.
{{declarations}}
void main()
{
    vec2 st = gl_FragCoord.xy / facet_resolution;
    vec3 n = vec3(sweep_n_x(st.x, st.y), sweep_n_y(st.x, st.y), sweep_n_z(st.x, st.y));
    vec3 l = vec3(sweep_l_x(st.x, st.y), sweep_l_y(st.x, st.y), sweep_l_z(st.x, st.y));
    vec3 v = vec3(sweep_v_x(st.x, st.y), sweep_v_y(st.x, st.y), sweep_v_z(st.x, st.y));
    facet_color = vec4(facet_reflect(n, l, v, facet_tangent(n){{coat_arg}}), 1.0);
}
