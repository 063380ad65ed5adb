
// ---- facet's MaterialX harness (tests/bench/materialx_bench.cpp): MaterialX's
// vertex data, filled from facet's cost frame instead of a vertex shader; the
// sphere of the scene "single" ray cast from gl_FragCoord, the tangent by
// MODELS.md's rule. MaterialX's own main, renamed mx_main, shades with its light
// uniforms set to the scene's one light.
vec3 facet_tangent(vec3 n)
{
    vec3 t = cross(vec3(0.0, 1.0, 0.0), n);
    if (length(t) < 1e-4) t = cross(vec3(1.0, 0.0, 0.0), n);
    return normalize(t);
}

void main()
{
    vec3 dir, p, n;
    if (!facet_camera_hit(dir, p, n)) {
        out1 = vec4(0.0);
        return;
    }
{{vertex_data}}
    mx_main();
}
