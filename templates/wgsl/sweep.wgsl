
// ---- facet's robustness sweep: each pixel centre is one direction set of the grid
// (targets/sweep_grid.h); the output is the raw reflectance, NaN and Inf included.
@group(0) @binding(0) var<uniform> facet_resolution: vec4<f32>;  // xy: the grid's side, in pixels

// One triangle over the whole framebuffer.
@vertex
fn facet_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn facet_sweep(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    let st = pixel.xy / facet_resolution.xy;
    let n = vec3<f32>(sweep_n_x(st.x, st.y), sweep_n_y(st.x, st.y), sweep_n_z(st.x, st.y));
    let l = vec3<f32>(sweep_l_x(st.x, st.y), sweep_l_y(st.x, st.y), sweep_l_z(st.x, st.y));
    let v = vec3<f32>(sweep_v_x(st.x, st.y), sweep_v_y(st.x, st.y), sweep_v_z(st.x, st.y));
    return vec4<f32>(facet_reflect(n, l, v, facet_tangent(n){{coat_arg}}), 1.0);
}
