
// ---- facet's validation ray caster: the scene's analytic spheres and squares,
// one ray per pixel centre (gl_FragCoord), shadows by shadow rays.
#define FACET_MAX_OBJECTS 8
uniform vec2 facet_resolution;
uniform vec3 facet_camera_forward;
uniform vec3 facet_camera_right;
uniform vec3 facet_camera_up;
uniform vec2 facet_camera_tan;                       // tan(fov/2) · (aspect, 1)
uniform int facet_object_count;
uniform vec4 facet_object_shape[FACET_MAX_OBJECTS];  // sphere: centre, radius; square: centre, half-side
uniform vec4 facet_object_normal[FACET_MAX_OBJECTS]; // square: normal, w = 1; sphere: w = 0
uniform vec4 facet_object_axis[FACET_MAX_OBJECTS];   // square: the in-plane axis u (v = normal × u)
uniform float facet_shadow_offset;                   // shadow rays start this far out
out vec4 facet_color;
// The object being shaded: every object is convex, so it cannot shadow itself
// where n·l > 0, and a float hit point just inside it must not make it try.
int facet_shaded_object = -1;

// The nearest hit of origin + t·dir with t > t_min, or -1.
float facet_intersect(int i, vec3 origin, vec3 dir, float t_min)
{
    vec4 s = facet_object_shape[i];
    if (facet_object_normal[i].w == 0.0) {
        vec3 oc = origin - s.xyz;
        float b = dot(oc, dir);
        float c = dot(oc, oc) - s.w * s.w;
        float disc = b * b - c;
        if (disc < 0.0) return -1.0;
        float q = b > 0.0 ? -(b + sqrt(disc)) : -(b - sqrt(disc));  // no cancellation
        float t0 = q, t1 = c / q;
        if (t0 > t1) { float x = t0; t0 = t1; t1 = x; }
        if (t0 > t_min) return t0;
        if (t1 > t_min) return t1;
        return -1.0;
    }
    vec3 n = facet_object_normal[i].xyz;
    float den = dot(dir, n);
    if (den == 0.0) return -1.0;
    float t = dot(s.xyz - origin, n) / den;
    if (!(t > t_min)) return -1.0;
    vec3 q = origin + dir * t - s.xyz;
    vec3 u = facet_object_axis[i].xyz;
    vec3 v = cross(n, u);
    if (abs(dot(q, u)) > s.w || abs(dot(q, v)) > s.w) return -1.0;
    return t;
}

float facet_visibility(vec3 p, vec3 l, float d)
{
    for (int i = 0; i < FACET_MAX_OBJECTS; ++i) {
        if (i >= facet_object_count) break;
        if (i == facet_shaded_object) continue;
        float t = facet_intersect(i, p, l, facet_shadow_offset);
        if (t > 0.0 && t < d) return 0.0;
    }
    return 1.0;
}

void main()
{
    vec2 ndc = 2.0 * gl_FragCoord.xy / facet_resolution - 1.0;
    vec3 dir = normalize(facet_camera_forward + facet_camera_right * (ndc.x * facet_camera_tan.x)
                         + facet_camera_up * (ndc.y * facet_camera_tan.y));
    float best = -1.0;
    int hit = -1;
    for (int i = 0; i < FACET_MAX_OBJECTS; ++i) {
        if (i >= facet_object_count) break;
        float t = facet_intersect(i, facet_camera_position, dir, 0.0);
        if (t > 0.0 && (best < 0.0 || t < best)) { best = t; hit = i; }
    }
    if (hit < 0) {
        facet_color = vec4(0.0);
        return;
    }
    vec3 p = facet_camera_position + dir * best;
    facet_shaded_object = hit;
    vec3 n = facet_object_normal[hit].w == 0.0 ? normalize(p - facet_object_shape[hit].xyz)
                                               : facet_object_normal[hit].xyz;
    facet_color = vec4(facet_shade(p, n, -dir, facet_tangent(n)), 1.0);
}
