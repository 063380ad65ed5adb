
// ---- facet's cost frame (analysis/cost.h): the built-in scene "single" drawn over the
// full-screen triangle, one ray per pixel centre (gl_FragCoord) against its sphere,
// shaded by its one point light: no attenuation, no shadow test, no light loop.
// llvmpipe executes every unrolled iteration and both sides of every branch, so a
// loop over FACET_MAX_LIGHTS would charge every material for eight lights; this
// frame is the same for every material (and for other generators' shaders, which
// tests/bench/materialx_bench.cpp puts under it).
uniform vec2 facet_resolution;
uniform vec3 facet_camera_position;
uniform vec3 facet_camera_forward;
uniform vec3 facet_camera_right;
uniform vec3 facet_camera_up;
uniform vec2 facet_camera_tan;      // tan(fov/2) · (aspect, 1)
uniform vec4 facet_sphere;          // centre, radius
uniform vec3 facet_light_position;
uniform vec3 facet_light_color;
uniform vec3 facet_ambient;

// The camera ray through this pixel centre and where it meets the sphere, with the
// normal there; false where it misses.
bool facet_camera_hit(out vec3 dir, out vec3 p, out vec3 n)
{
    vec2 ndc = 2.0 * gl_FragCoord.xy / facet_resolution - 1.0;
    dir = normalize(facet_camera_forward + facet_camera_right * (ndc.x * facet_camera_tan.x)
                    + facet_camera_up * (ndc.y * facet_camera_tan.y));
    vec3 oc = facet_camera_position - facet_sphere.xyz;
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
