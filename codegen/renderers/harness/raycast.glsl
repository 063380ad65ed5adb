
// ---- facet's validation ray caster: the scene's analytic spheres and squares and its
// triangle meshes, one ray per pixel centre (gl_FragCoord), shadows by shadow rays. The
// objects, any number, are in a texture buffer under a bounding volume hierarchy over them
// (scene/bvh.h, object_bvh(): the one the reference walks), each mesh's triangles under its
// own. Each pass shades the objects of one material; the others are drawn black and the
// passes are summed. With FACET_GBUFFER defined, main writes the G-buffer (renderers/gbuffer.h)
// instead of shading: the six geometry images and two layers of the visibility image a draw
// (from facet_first_layer), one draw buffer each (GL 3.3 promises eight), which the other
// renderers' shading passes (templates/glsl/gbuffer_shade.glsl) read.
//
// A draw takes lights facet_light_first … + facet_light_count − 1 (facet_light(i) reads light
// facet_light_first + i): llvmpipe ends every loop of a shader invocation once they have turned
// 65,535 times in all (Mesa's gallivm, LP_MAX_TGSI_LOOP_ITERATIONS), and a pixel's shadow rays
// walk the hierarchies many turns a light (500 lights over 100 objects went past it). main then
// says so (facet_loops_cut()): the renderer draws the lights again in two halves.
uniform vec2 facet_resolution;
uniform vec3 facet_camera_forward;
uniform vec3 facet_camera_right;
uniform vec3 facet_camera_up;
uniform vec2 facet_camera_tan;          // tan(fov/2) · (aspect, 1); orthographic: half the height · (aspect, 1)
uniform int facet_camera_orthographic;  // 1: rays parallel to facet_camera_forward from the image plane
uniform int facet_object_count;
uniform samplerBuffer facet_objects;    // 4 texels an object, in the hierarchy's order: 0 its shape (sphere: centre,
                                        // radius; square: centre, half-side; mesh: first BVH node); 1 xyz the
                                        // square's normal, w the kind ({{sphere}} sphere, {{square}} square, {{mesh}} mesh);
                                        // 2 xyz the square's in-plane axis u (v = normal × u), w the object's
                                        // material pass; 3 x its index in the scene, and for a mesh with
                                        // vertex colours y its colours' first texel less 3 × its first
                                        // triangle's index (its triangle t's corners are at y + 3t), z 1
uniform samplerBuffer facet_scene_bvh;  // 2 texels a node: (lo, right child or first object), (hi, object count)
uniform samplerBuffer facet_bvh;        // the meshes': 2 texels a node: (lo, right child or first triangle), (hi, count)
uniform samplerBuffer facet_triangles;  // 6 texels a triangle: p0, p1, p2, n0, n1, n2
uniform samplerBuffer facet_texcoords;  // 3 texels a triangle: vertex k's (uv set 0, uv set 1)
uniform samplerBuffer facet_tangents;   // 3 texels a triangle: corner k's tangent (xyz, w), normal-mapped meshes
uniform samplerBuffer facet_colors;     // 3 texels a triangle of the meshes with vertex colours: corner k's RGBA
uniform samplerBuffer facet_cutouts;    // 5 texels an object, in the hierarchy's order, its cut-out (glTF's alphaMode
                                        // MASK): 0 (cutoff, or -1: opaque; factor; uv set; flags: 1 an image); 1 its image's
                                        // rectangle in the atlas (x0, y0, width, height); 2 and 3 KHR_texture_transform
                                        // (a, b, c, d), (ou, ov), wrap s + 4·t, 1 bilinear; 4 x the offset
uniform sampler2D facet_alpha_atlas;    // the cut-outs' alpha images one above another, the value in r
uniform int facet_pass;                 // the material pass drawn: its objects are shaded, the others drawn black
uniform int facet_probe_turns;          // 2: facet_loops_cut()'s loop (a uniform, so that no compiler unrolls it)
uniform float facet_shadow_offset;      // shadow rays start this far out
#ifdef FACET_GBUFFER
layout(location = 0) out vec4 facet_gbuffer_position;    // xyz p; w the material pass of the object hit, -1 background
layout(location = 1) out vec4 facet_gbuffer_normal;      // the unit normal n
layout(location = 2) out vec4 facet_gbuffer_view;        // v = -(the ray's unit direction)
layout(location = 3) out vec4 facet_gbuffer_uv_tangent;  // facet_uv_tangent_at(): t, w = ±1
layout(location = 4) out vec4 facet_gbuffer_uv;          // uv sets 0 (xy) and 1 (zw)
layout(location = 5) out vec4 facet_gbuffer_color0;      // facet_color0_at(): the vertex colour, RGBA
layout(location = 6) out vec4 facet_gbuffer_visibility_0;  // visibility layer facet_first_layer
layout(location = 7) out vec4 facet_gbuffer_visibility_1;  // … + 1
uniform int facet_first_layer;
#else
out vec4 facet_color;
#endif

// Texel k of object i (facet_objects).
vec4 facet_object(int i, int k)
{
    return texelFetch(facet_objects, 4 * i + k);
}

// The object and triangle being shaded: a sphere or a square is convex and
// cannot shadow itself where n·l > 0, nor can a flat triangle; a float hit
// point just inside them must not make them try.
int facet_shaded_object = -1;
int facet_shaded_triangle = -1;

struct FacetHit {
    float t;       // -1: no hit
    int triangle;  // meshes: the triangle hit
    vec2 uv;       // meshes: barycentrics of its second and third vertices
};

// Möller & Trumbore 1997, two-sided.
bool facet_ray_triangle(vec3 o, vec3 d, int tri, out float t, out vec2 uv)
{
    vec3 p0 = texelFetch(facet_triangles, tri * 6).xyz;
    vec3 e1 = texelFetch(facet_triangles, tri * 6 + 1).xyz - p0;
    vec3 e2 = texelFetch(facet_triangles, tri * 6 + 2).xyz - p0;
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (det == 0.0) return false;
    float inv = 1.0 / det;
    vec3 tv = o - p0;
    uv.x = dot(tv, pv) * inv;
    if (uv.x < 0.0 || uv.x > 1.0) return false;
    vec3 qv = cross(tv, e1);
    uv.y = dot(d, qv) * inv;
    if (uv.y < 0.0 || uv.x + uv.y > 1.0) return false;
    t = dot(e2, qv) * inv;
    return true;
}

bool facet_ray_box(vec3 o, vec3 inv_d, vec3 lo, vec3 hi, float t_max)
{
    vec3 a = (lo - o) * inv_d, b = (hi - o) * inv_d;
    vec3 near = min(a, b), far = max(a, b);
    float t0 = max(max(near.x, near.y), max(near.z, 0.0));
    float t1 = min(min(far.x, far.y), min(far.z, t_max));
    return t0 <= t1;
}

FacetHit facet_intersect_mesh(int first_node, vec3 o, vec3 d, float t_min, int skip)
{
    FacetHit h = FacetHit(-1.0, -1, vec2(0.0));
    float best = 1e30;
    vec3 inv_d = 1.0 / d;
    int stack[32];
    int top = 0;
    stack[top++] = first_node;
    while (top > 0) {
        int node = stack[--top];
        vec4 a = texelFetch(facet_bvh, node * 2), b = texelFetch(facet_bvh, node * 2 + 1);
        if (!facet_ray_box(o, inv_d, a.xyz, b.xyz, best)) continue;
        int count = int(b.w);
        if (count > 0) {
            for (int k = 0; k < count; ++k) {
                int tri = int(a.w) + k;
                float t;
                vec2 uv;
                if (tri != skip && facet_ray_triangle(o, d, tri, t, uv) && t > t_min && t < best) {
                    best = t;
                    h = FacetHit(t, tri, uv);
                }
            }
        } else if (top < 30) {
            stack[top++] = int(a.w);
            stack[top++] = node + 1;
        }
    }
    return h;
}

// The nearest hit of origin + t·dir with t > t_min, or t = -1.
FacetHit facet_intersect(int i, vec3 origin, vec3 dir, float t_min, int skip)
{
    FacetHit none = FacetHit(-1.0, -1, vec2(0.0));
    vec4 s = facet_object(i, 0);
    float kind = facet_object(i, 1).w;
    if (kind == {{sphere}}.0) {
        vec3 oc = origin - s.xyz;
        float b = dot(oc, dir);
        float c = dot(oc, oc) - s.w * s.w;
        // r² − |oc − b·dir|², not b² − c: for a small sphere far away b² and c are nearly equal and
        // their difference loses most of float's digits (a hit point of a sphere of radius 0.25 at
        // 13 units was 1e-4 off; Haines et al., "Precision Improvements for Ray/Sphere
        // Intersection", Ray Tracing Gems, 2019). dir is a unit vector.
        vec3 h = oc - b * dir;
        float disc = s.w * s.w - dot(h, h);
        if (disc < 0.0) return none;
        float q = b > 0.0 ? -(b + sqrt(disc)) : -(b - sqrt(disc));  // no cancellation
        float t0 = q, t1 = c / q;
        if (t0 > t1) { float x = t0; t0 = t1; t1 = x; }
        if (t0 > t_min) return FacetHit(t0, -1, vec2(0.0));
        if (t1 > t_min) return FacetHit(t1, -1, vec2(0.0));
        return none;
    }
    if (kind == {{mesh}}.0) return facet_intersect_mesh(int(s.x), origin, dir, t_min, skip);
    vec3 n = facet_object(i, 1).xyz;
    float den = dot(dir, n);
    if (den == 0.0) return none;
    float t = dot(s.xyz - origin, n) / den;
    if (!(t > t_min)) return none;
    vec3 q = origin + dir * t - s.xyz;
    vec3 u = facet_object(i, 2).xyz;
    vec3 v = cross(n, u);
    if (abs(dot(q, u)) > s.w || abs(dot(q, v)) > s.w) return none;
    return FacetHit(t, -1, vec2(0.0));
}

// ---- Cut-outs (glTF 2.0 §3.9.4, alphaMode MASK): the surface is there where alpha ≥ cutoff.
// alpha = clamp(offset + factor · the image's value at KHR_texture_transform(uv) · vc, 0, 1),
// the image sampled by docs/textures.md's rule (templates/glsl/textures.glsl's), vc the vertex
// colour's component where the alpha reads it (glTF's base colour alpha times COLOR_0's):
// camera and shadow rays alike pass the surface where it is cut out.
vec2 facet_uv(int i, vec3 p, FacetHit h, int set);
vec4 facet_color0_at(int i, FacetHit h);

vec4 facet_cutout(int i, int k)
{
    return texelFetch(facet_cutouts, 5 * i + k);
}

// A texel index wrapped into [0, size): 0 repeat, 1 clamp, 2 mirror (as facet_wrap).
int facet_cutout_wrap(int i, int size, int mode)
{
    if (mode == 1) return clamp(i, 0, size - 1);
    int period = mode == 2 ? 2 * size : size;
    int m = i - period * int(floor(float(i) / float(period)));
    return m < size ? m : period - 1 - m;
}

float facet_cutout_texel(ivec4 rect, int i, int j, ivec2 wrap)
{
    ivec2 at = rect.xy + ivec2(facet_cutout_wrap(i, rect.z, wrap.x), facet_cutout_wrap(j, rect.w, wrap.y));
    return texelFetch(facet_alpha_atlas, at, 0).r;
}

// The cut-out's image at the hit, where it has one (facet_alpha()).
float facet_alpha_image(int i, vec3 p, FacetHit h)
{
    vec4 c = facet_cutout(i, 0);
    vec4 m = facet_cutout(i, 2), e = facet_cutout(i, 3);
    vec2 uv = facet_uv(i, p, h, int(c.z));
    uv = vec2(m.x * uv.x + m.y * uv.y + e.x, m.z * uv.x + m.w * uv.y + e.y);
    ivec4 rect = ivec4(facet_cutout(i, 1));
    ivec2 wrap = ivec2(int(e.z) % 4, int(e.z) / 4);
    vec2 x = uv * vec2(rect.zw);
    float a;
    if (e.w == 0.0) {
        a = facet_cutout_texel(rect, int(floor(x.x)), int(floor(x.y)), wrap);
    } else {
        x -= 0.5;
        vec2 f = floor(x), w = x - f;
        int s = int(f.x), t = int(f.y);
        a = mix(mix(facet_cutout_texel(rect, s, t, wrap), facet_cutout_texel(rect, s + 1, t, wrap), w.x),
                mix(facet_cutout_texel(rect, s, t + 1, wrap), facet_cutout_texel(rect, s + 1, t + 1, wrap), w.x), w.y);
    }
    return a;
}

float facet_alpha(int i, vec3 p, FacetHit h)
{
    vec4 c = facet_cutout(i, 0);
    int flags = int(c.w);
    float a = c.y;
    if ((flags & 1) != 0) a *= facet_alpha_image(i, p, h);
    return clamp(facet_cutout(i, 4).x + a, 0.0, 1.0);
}

// The nearest hit of object i beyond t_min (skipping triangle `skip`) that its cut-out keeps:
// past each hit cut out, the search goes on.
FacetHit facet_intersect_kept(int i, vec3 origin, vec3 dir, float t_min, int skip)
{
    FacetHit h = facet_intersect(i, origin, dir, t_min, skip);
    float cutoff = facet_cutout(i, 0).x;
    if (cutoff < 0.0) return h;
    for (int k = 0; k < 64 && h.t > 0.0; ++k) {
        if (facet_alpha(i, origin + dir * h.t, h) >= cutoff) return h;
        h = facet_intersect(i, origin, dir, h.t, h.triangle);
    }
    return FacetHit(-1.0, -1, vec2(0.0));
}

// Does the ray origin + t·dir enter node `node` of the objects' hierarchy at some t in
// [0, t_max]? Its texels in a and b.
bool facet_enters(int node, vec3 origin, vec3 inv_d, float t_max, out vec4 a, out vec4 b)
{
    a = texelFetch(facet_scene_bvh, node * 2);
    b = texelFetch(facet_scene_bvh, node * 2 + 1);
    return facet_ray_box(origin, inv_d, a.xyz, b.xyz, t_max);
}

// Every light alike: a shadow ray from p towards it (`light` unused), through the objects
// whose boxes it enters before d.
float facet_visibility(vec3 p, vec3 l, float d, int light)
{
    if (facet_object_count == 0) return 1.0;
    vec3 inv_d = 1.0 / l;
    int stack[32];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        int node = stack[--top];
        vec4 a, b;
        if (!facet_enters(node, p, inv_d, d, a, b)) continue;
        int count = int(b.w);
        if (count == 0) {
            if (top < 30) {  // a median split's depth is log2(objects): far below
                stack[top++] = int(a.w);
                stack[top++] = node + 1;
            }
            continue;
        }
        for (int k = 0; k < count; ++k) {
            int i = int(a.w) + k;
            bool own = i == facet_shaded_object;
            if (own && facet_object(i, 1).w != {{mesh}}.0) continue;
            FacetHit h = facet_intersect_kept(i, p, l, facet_shadow_offset, own ? facet_shaded_triangle : -1);
            if (h.t > 0.0 && h.t < d) return 0.0;
        }
    }
    return 1.0;
}

// The object the ray origin + t·dir (t > 0) meets first, its hit in `best`; -1 when none.
// Among equally near ones the lowest scene index, as the reference picks.
int facet_nearest(vec3 origin, vec3 dir, out FacetHit best)
{
    best = FacetHit(-1.0, -1, vec2(0.0));
    int hit = -1;
    if (facet_object_count == 0) return hit;
    vec3 inv_d = 1.0 / dir;
    int stack[32];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        int node = stack[--top];
        vec4 a, b;
        if (!facet_enters(node, origin, inv_d, best.t < 0.0 ? 1e30 : best.t, a, b)) continue;
        int count = int(b.w);
        if (count == 0) {
            if (top < 30) {
                stack[top++] = int(a.w);
                stack[top++] = node + 1;
            }
            continue;
        }
        for (int k = 0; k < count; ++k) {
            int i = int(a.w) + k;
            FacetHit h = facet_intersect_kept(i, origin, dir, 0.0, -1);
            if (h.t > 0.0 && (best.t < 0.0 || h.t < best.t
                              || (h.t == best.t && facet_object(i, 3).x < facet_object(hit, 3).x))) {
                best = h;
                hit = i;
            }
        }
    }
    return hit;
}

// docs/textures.md: texture coordinates set `set` at p. A sphere's: longitude from +z
// towards +x, latitude from the +y pole (v = 0 at the top); a square's: along its axes,
// [0, 1]² edge to edge, v down the second axis; a mesh's: its vertices', blended
// barycentrically.
vec2 facet_uv(int i, vec3 p, FacetHit h, int set)
{
    float kind = facet_object(i, 1).w;
    vec4 s = facet_object(i, 0);
    if (kind == {{sphere}}.0) {
        vec3 d = (p - s.xyz) / s.w;
        return vec2(0.5 + atan(d.x, d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
    }
    if (kind == {{square}}.0) {
        vec3 a = facet_object(i, 2).xyz;
        vec3 b = cross(facet_object(i, 1).xyz, a);
        vec3 q = p - s.xyz;
        return vec2(0.5 + dot(q, a) / (2.0 * s.w), 0.5 - dot(q, b) / (2.0 * s.w));
    }
    int t = h.triangle * 3;
    vec4 t0 = texelFetch(facet_texcoords, t), t1 = texelFetch(facet_texcoords, t + 1), t2 = texelFetch(facet_texcoords, t + 2);
    vec4 st = t0 * (1.0 - h.uv.x - h.uv.y) + t1 * h.uv.x + t2 * h.uv.y;
    return set == 0 ? st.xy : st.zw;
}

// docs/textures.md, "Tangent frames": (t, w) at p, for a normal map: t the unit ∂p/∂u, B = w·(n × t).
// A sphere's: normalize(d_z, 0, −d_x); a square's: its first axis; w = +1. A mesh's: the
// barycentric blend of its corners' tangents, w the sign of their blended w.
vec4 facet_uv_tangent_at(int i, vec3 p, FacetHit h)
{
    float kind = facet_object(i, 1).w;
    if (kind == {{sphere}}.0) {
        vec3 d = p - facet_object(i, 0).xyz;
        return vec4(normalize(vec3(d.z, 0.0, -d.x)), 1.0);
    }
    if (kind == {{square}}.0) return vec4(facet_object(i, 2).xyz, 1.0);
    int t = h.triangle * 3;
    vec4 c = texelFetch(facet_tangents, t) * (1.0 - h.uv.x - h.uv.y) + texelFetch(facet_tangents, t + 1) * h.uv.x
             + texelFetch(facet_tangents, t + 2) * h.uv.y;
    return vec4(c.xyz, c.w >= 0.0 ? 1.0 : -1.0);
}

// The vertex colour at the hit (glTF's COLOR_0, RGBA): a mesh's corners' colours blended
// barycentrically, as its uv are; white on spheres, squares and meshes without colours.
vec4 facet_color0_at(int i, FacetHit h)
{
    vec4 c = facet_object(i, 3);
    if (facet_object(i, 1).w != {{mesh}}.0 || c.z == 0.0) return vec4(1.0);
    int t = int(c.y) + h.triangle * 3;
    return texelFetch(facet_colors, t) * (1.0 - h.uv.x - h.uv.y) + texelFetch(facet_colors, t + 1) * h.uv.x
           + texelFetch(facet_colors, t + 2) * h.uv.y;
}

// Where the camera ray through this pixel starts: the eye, or (orthographic) its point of the image plane.
vec3 facet_ray_origin;

// The camera ray through this pixel centre (facet_ray_origin, dir) and the nearest object
// it meets (best); -1 when none.
int facet_camera_hit(out vec3 dir, out FacetHit best)
{
    vec2 ndc = 2.0 * gl_FragCoord.xy / facet_resolution - 1.0;
    vec3 across = facet_camera_right * (ndc.x * facet_camera_tan.x) + facet_camera_up * (ndc.y * facet_camera_tan.y);
    if (facet_camera_orthographic != 0) {
        facet_ray_origin = facet_camera_position + across;
        dir = facet_camera_forward;
    } else {
        facet_ray_origin = facet_camera_position;
        dir = normalize(facet_camera_forward + across);
    }
    return facet_nearest(facet_ray_origin, dir, best);
}

// Object `hit`'s unit normal at p (a mesh's: its vertices' normals blended).
vec3 facet_normal_at(int hit, vec3 p, FacetHit best)
{
    float kind = facet_object(hit, 1).w;
    if (kind == {{sphere}}.0) return normalize(p - facet_object(hit, 0).xyz);
    if (kind == {{square}}.0) return facet_object(hit, 1).xyz;
    int t = best.triangle * 6;
    return normalize(texelFetch(facet_triangles, t + 3).xyz * (1.0 - best.uv.x - best.uv.y)
                     + texelFetch(facet_triangles, t + 4).xyz * best.uv.x
                     + texelFetch(facet_triangles, t + 5).xyz * best.uv.y);
}

// Whether this invocation ran out of llvmpipe's loop turns, every loop since cut short after
// one turn: a loop of facet_probe_turns turns then turns once. Elsewhere, never.
bool facet_loops_cut()
{
    int turns = 0;
    for (int k = 0; k < facet_probe_turns; ++k) ++turns;
    return turns < facet_probe_turns;
}

#ifndef FACET_GBUFFER
// This pixel's colour: its lights facet_light_first … (the ambient and emitted terms with the first).
vec4 facet_pixel()
{
    vec3 dir;
    FacetHit best;
    int hit = facet_camera_hit(dir, best);
    if (hit < 0) return vec4(0.0);
    if (int(facet_object(hit, 2).w) != facet_pass) return vec4(0.0, 0.0, 0.0, 1.0);
    vec3 p = facet_ray_origin + dir * best.t;
    facet_shaded_object = hit;
    facet_shaded_triangle = best.triangle;
    vec3 n = facet_normal_at(hit, p, best);
{{sample}}    vec3 color = facet_shade(p, n, -dir, facet_tangent(n));
    // The renderer sets the ambient colour to 0 past the first lights; the emitted term stays.
    if (facet_light_first > 0) color -= facet_emitted(n, -dir);
    return vec4(color, 1.0);
}

// Alpha −1: this pixel's loops were cut short (facet_loops_cut()).
void main()
{
    vec4 color = facet_pixel();
    facet_color = facet_loops_cut() ? vec4(0.0, 0.0, 0.0, -1.0) : color;
}
#else
// 1 when light i reaches p (its shadow ray is clear), 0 in shadow; 0 without a shadow ray
// where the surface faces away from it by more than {{horizon}} (n·l < -{{horizon}}): the
// light loop asks only where n·l > 0, and no renderer's rounding of n·l comes near that.
int facet_light_bit(int i, vec3 p, vec3 n)
{
    FacetLight light = facet_light(i);
    vec3 l;
    float d = 1e30;  // directional lights have no distance
    if (light.position.w == {{directional}}.0) {
        l = -normalize(light.position.xyz);
    } else {
        vec3 to_light = light.position.xyz - p;
        d = length(to_light);
        l = to_light / d;
    }
    if (dot(n, l) < -{{horizon}}) return 0;
    return facet_visibility(p, l, d, i) > 0.0 ? 1 : 0;
}

// Layer `layer` of the visibility image at p: light i's bit is bit i mod {{bits}} of channel
// (i / {{bits}}) mod 4 of layer i / {{layer_lights}}, each channel an integer below 2^{{bits}}
// (exact in float32); 0 for the lights this draw does not take (another draw's bits add up
// with these) and beyond the scene's lights.
vec4 facet_visibility_layer(int layer, vec3 p, vec3 n)
{
    vec4 word = vec4(0.0);
    for (int c = 0; c < 4; ++c) {
        int bits = 0;
        for (int k = 0; k < {{bits}}; ++k) {
            int j = layer * {{layer_lights}} + c * {{bits}} + k - facet_light_first;  // this draw's light j
            if (j >= 0 && j < facet_light_count) bits |= facet_light_bit(j, p, n) << k;
        }
        word[c] = float(bits);
    }
    return word;
}

void facet_cast()
{
    vec3 dir;
    FacetHit best;
    int hit = facet_camera_hit(dir, best);
    facet_gbuffer_position = vec4(0.0, 0.0, 0.0, hit < 0 ? -1.0 : facet_object(hit, 2).w);
    facet_gbuffer_normal = facet_gbuffer_view = facet_gbuffer_uv_tangent = facet_gbuffer_uv = vec4(0.0);
    facet_gbuffer_color0 = facet_gbuffer_visibility_0 = facet_gbuffer_visibility_1 = vec4(0.0);
    if (hit < 0) return;
    vec3 p = facet_ray_origin + dir * best.t;
    facet_shaded_object = hit;
    facet_shaded_triangle = best.triangle;
    vec3 n = facet_normal_at(hit, p, best);
    facet_gbuffer_position.xyz = p;
    facet_gbuffer_normal = vec4(n, 0.0);
    facet_gbuffer_view = vec4(-dir, 0.0);
    facet_gbuffer_uv_tangent = facet_uv_tangent_at(hit, p, best);
    facet_gbuffer_uv = vec4(facet_uv(hit, p, best, 0), facet_uv(hit, p, best, 1));
    facet_gbuffer_color0 = facet_color0_at(hit, best);
    facet_gbuffer_visibility_0 = facet_visibility_layer(facet_first_layer, p, n);
    facet_gbuffer_visibility_1 = facet_visibility_layer(facet_first_layer + 1, p, n);
}

// The visibility −1 everywhere: this pixel's loops were cut short (facet_loops_cut()).
void main()
{
    facet_cast();
    if (facet_loops_cut()) facet_gbuffer_visibility_0 = facet_gbuffer_visibility_1 = vec4(-1.0);
}
#endif
