#include "reference/raycaster.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "catalog/texture.h"
#include "core/parallel.h"
#include "scene/bvh.h"
#include "scene/tangents.h"
#include "reference/interpreter.h"

namespace facet {

namespace {

struct SceneHit {
  Hit hit;
  int object = -1;
  bool fragile = false;  // a cut-out's alpha at the hit, or on the way to it, lies at its cutoff
};

// Per object: its material where that cuts the surface out (Material::masked()), else null.
using Cutouts = std::vector<const Material*>;

// A cut-out's alpha this close to its cutoff keeps or drops the surface as each renderer's
// rounding goes (float32 sampling): such pixels are fragile, as grazing shadow rays are.
constexpr double kAlphaMargin = 1e-4;

// Whether the surface of `o` is there at hit `h` (point p) under the cut-out of material `m`:
// alpha ≥ cutoff (glTF 2.0 §3.9.4, alphaMode MASK). An alpha from an image or the vertex
// colour (its alpha, glTF's base colour alpha times COLOR_0's) is sampled there; a number is itself.
bool present(const Object& o, const Material& m, const Vec3& p, const Hit& h, bool& fragile) {
  bool edge = false;
  double alpha = m.alpha.number;  // a number: the same everywhere
  if (m.alpha.texture) {  // an image's channel, the vertex colour's alpha, or both
    const auto uv = o.uv_at(p, h);
    const size_t set = size_t(m.alpha.texture->uv);
    alpha = texture_value(m.alpha, alpha_param().range, uv[set][0], uv[set][1], &edge, o.color_at(h))[0];
  }
  fragile = fragile || edge || std::fabs(alpha - *m.alpha_cutoff) < kAlphaMargin;
  return alpha >= *m.alpha_cutoff;
}

// The nearest hit of `o` beyond t_min (skipping triangle `skip`) that its cut-out keeps: each
// hit cut out, the search goes on past it.
Hit kept_hit(const Object& o, const Material* cut, const Vec3& origin, const Vec3& dir, double t_min, int skip,
             bool& fragile) {
  Hit h = o.hit(origin, dir, t_min, skip);
  while (cut && h.ok() && !present(o, *cut, origin + dir * h.t, h, fragile)) h = o.hit(origin, dir, h.t, h.triangle);
  return h;
}

// The object the ray meets first (the lowest index among equally near ones, as a loop over
// the objects in order finds it), walking the objects' hierarchy.
SceneHit nearest(const Scene& s, const ObjectBvh& bvh, const Cutouts& cut, const Vec3& o, const Vec3& d) {
  SceneHit best;
  bvh.walk(o, d, [&] { return best.object < 0 ? INFINITY : best.hit.t; }, [&](uint32_t i) {
    bool fragile = false;
    Hit h = kept_hit(s.objects[i], cut[i], o, d, 0, -1, fragile);
    best.fragile = best.fragile || fragile;
    if (h.ok() && (best.object < 0 || h.t < best.hit.t || (h.t == best.hit.t && int(i) < best.object)))
      best = {h, int(i), best.fragile};
    return true;
  });
  return best;
}

// A mesh as an occluder: every triangle the segment's line crosses within
// (t_min, t_max), with its barycentric margin (> 0 inside, < 0 outside).
void mesh_occlusion(const Mesh& m, const Vec3& o, const Vec3& d, double t_min, double t_max, double t_close,
                    int skip, bool& hit, bool& clear, bool& near) {
  m.candidates(o, d, t_max, 2 * kGrazing, [&](int i) {
    if (i == skip) return;
    const auto& k = m.triangles[size_t(i)];
    Vec3 p0 = m.positions[k[0]], e1 = m.positions[k[1]] - p0, e2 = m.positions[k[2]] - p0;
    Vec3 pv = cross(d, e2);
    double det = dot(e1, pv);
    if (det == 0) return;
    Vec3 tv = o - p0;
    double u = dot(tv, pv) / det, v = dot(d, cross(tv, e1)) / det, t = dot(e2, cross(tv, e1)) / det;
    if (!(t > t_min && t < t_max)) return;
    double margin = std::min({u, v, 1 - u - v});
    if (margin >= 0) hit = true;
    // A block right at the surface point (a smooth normal's shadow ray dipping
    // under the neighbouring triangle) is as fragile as an edge.
    if (margin >= kGrazing && t > t_close) clear = true;
    else if (margin > -kGrazing) near = true;
  });
}

// Object o as an occluder of the segment p + s·l, s ∈ (offset, dist) (blocked(), below):
// `hit` where the segment meets it, `clear` where it does so away from its edges, `near` where
// it passes within kGrazing of one. `skip`: the shading triangle of a mesh.
void occlusion(const Object& o, const Vec3& p, const Vec3& l, double dist, double offset, double close, int skip,
               bool& hit, bool& clear, bool& near) {
  if (o.type == Object::Type::Sphere) {
    // Closest approach of the ray's line to the centre, ahead of p.
    double along = dot(o.center - p, l);
    double miss = length(o.center - (p + l * along));
    double t = o.intersect(p, l, offset);
    if (t > 0 && t < dist) {
      hit = true;
      if (miss < o.radius * (1 - kGrazing)) clear = true;
    }
    if (along > offset && along - o.radius < dist && std::fabs(miss - o.radius) < kGrazing * o.radius) near = true;
  } else if (o.type == Object::Type::Plane) {
    double den = dot(l, o.normal);
    if (den == 0) return;
    double t = dot(o.point - p, o.normal) / den;
    if (!(t > offset && t < dist)) return;
    Vec3 q = p + l * t - o.point, u, v;
    o.plane_axes(u, v);
    double edge = std::max(std::fabs(dot(q, u)), std::fabs(dot(q, v)));
    if (edge <= o.size) hit = true;
    if (edge <= o.size * (1 - kGrazing)) clear = true;
    else if (std::fabs(edge - o.size) < kGrazing * o.size) near = true;
  } else {
    mesh_occlusion(*o.mesh, p, l, offset, dist, close, skip, hit, clear, near);
  }
}

// A cut-out object as an occluder: it blocks where a hit before the light is kept, clearly
// where that hit is away from the object's edges (a sphere's silhouette, a square's border, a
// mesh triangle's edges, and a smooth normal's shadow ray dipping under the neighbouring
// triangle, as for opaque objects); the segment passing near an edge is fragile as ever.
void cutout_occlusion(const Object& o, const Material& cut, const Vec3& p, const Vec3& l, double dist, double offset,
                      double close, int skip, bool& hit, bool& clear, bool& near) {
  bool met = false, away = false;
  occlusion(o, p, l, dist, offset, close, skip, met, away, near);
  const Hit h = kept_hit(o, &cut, p, l, offset, skip, near);
  if (!(h.ok() && h.t < dist)) return;
  hit = true;
  if (o.type == Object::Type::Mesh) away = std::min({h.u, h.v, 1 - h.u - h.v}) >= kGrazing && h.t > close;
  if (away) clear = true;
  else near = true;
}

// Is the segment p + s·l, s ∈ (offset, dist), blocked? `self` cannot shadow
// itself when convex; a mesh skips the shading triangle. `grazing` is set when
// the segment passes within kGrazing of an occluder's edge and nothing blocks
// it clearly: which side such a ray falls on is a matter of rounding. Only the objects
// whose boxes the segment enters can block it or come that close (scene/bvh.h,
// object_box); once one blocks it clearly, the others change nothing.
bool blocked(const Scene& s, const ObjectBvh& bvh, const Cutouts& cut, int self, int self_triangle, const Vec3& p,
             const Vec3& l, double dist, double offset, double close, bool& grazing) {
  bool hit = false, clear = false, near = false;
  bvh.walk(p, l, [&] { return dist; }, [&](uint32_t i) {
    const Object& o = s.objects[i];
    bool own = int(i) == self;
    if (own && o.convex()) return true;
    const int skip = own ? self_triangle : -1;
    if (cut[i]) cutout_occlusion(o, *cut[i], p, l, dist, offset, close, skip, hit, clear, near);
    else occlusion(o, p, l, dist, offset, close, skip, hit, clear, near);
    return !clear;
  });
  if (near && !clear) grazing = true;
  return hit;
}

double scene_scale(const Scene& s) {
  double r = length(s.camera.position);
  for (const auto& o : s.objects) {
    Vec3 c;
    double radius;
    o.bounds(c, radius);
    r = std::max(r, length(c) + radius);
  }
  return std::max(r, 1.0);
}

// The frame a pixel is shaded in: the normal that decides which lights are above the
// surface (the object's own), the normal and tangent the lobes read (a normal map's), the
// textured parameters' values, the coat's own normal, and whether the pixel is fragile (grazing).
struct ShadingFrame {
  Vec3 n, shading_n, t;
  double w = 1;  // b = w·(n × t): the texture frame's handedness where t is that frame's
  Vec3 coat_n;  // the clear coat's normal (Material::coat_normal_differs): the object's own
  ShadingInputs textured;
  bool grazing = false;
};

// A mesh's corner tangents (scene/tangents.h) where its material has a normal map, else empty.
using CornerTangents = std::vector<std::array<double, 4>>;

ShadingFrame shading_frame(const Object& obj, const Reference& ref, const CornerTangents& corners, const Vec3& p,
                           const Hit& hit, const Vec3& v) {
  const Material& m = ref.material();
  ShadingFrame f;
  f.n = f.shading_n = f.coat_n = obj.normal_at(p, hit);
  f.t = tangent_rule(f.n, Vec3(m.tangent_axis));
  if (!ref.program().has_textures()) return f;
  // A texel's edge under nearest filtering, or where a sphere's mapping is not continuous
  // (the seam u = 0 | 1, the poles), is as fragile as a grazing shadow ray.
  const auto uv = obj.uv_at(p, hit);
  f.grazing = ref.sample_textures(uv, f.textured, obj.color_at(hit));
  if (obj.type == Object::Type::Sphere) {
    Vec3 d = (p - obj.center) / obj.radius;
    f.grazing = f.grazing || std::hypot(d.x, d.z) < 1e-3 || (d.z < 0 && std::fabs(d.x) < kTexelEdgeMargin * 2 * M_PI);
  }
  Vec3 tangent;
  double w = 1;
  const bool framed = obj.type == Object::Type::Mesh ? !corners.empty() : obj.tangent_at(p, hit, tangent, w);
  if (obj.type == Object::Type::Mesh && framed) blend_tangent(*obj.mesh, corners, hit, tangent, w);
  if (m.normal_map && framed) {
    f.shading_n = ref.mapped_normal(uv, f.n, tangent, w, f.grazing);
    f.t = follow_normal(f.t, f.shading_n);
    // The horizon rule jumps where the mapped normal turns from the eye.
    f.grazing = f.grazing || std::fabs(dot(f.shading_n, v)) < kNormalMapHorizon;
  }
  // KHR_materials_anisotropy: the lobes' tangent is the mesh's (the texture frame's), ⟂ their normal.
  if (ref.program().uv_tangent() && framed) {
    f.t = follow_normal(tangent, f.shading_n);
    f.w = w;
  }
  if (m.coat_normal_map && framed) f.coat_n = ref.mapped_normal(uv, f.n, tangent, w, f.grazing, true);
  // The coat's horizon (its ρ is 0 where c·v ≤ 0) jumps where its normal turns from the eye.
  if (m.coat_normal_differs() && framed)
    f.grazing = f.grazing || std::fabs(dot(f.coat_n, v)) < kNormalMapHorizon;
  return f;
}

// One pixel: the nearest object at its centre, shaded by every light that reaches it.
void shade_pixel(const Scene& s, const ObjectBvh& bvh, const Cutouts& cut, const std::vector<const Reference*>& shading,
                 const std::vector<CornerTangents>& tangents, double offset, double close, int x, int y, Render& r) {
  const int width = r.image.width, height = r.image.height;
  Vec3 eye;
  Vec3 dir = s.camera.ray(x, y, width, height, &eye);
  SceneHit h = nearest(s, bvh, cut, eye, dir);
  size_t idx = size_t(y) * size_t(width) + size_t(x);
  r.grazing[idx] = h.fragile;
  if (h.object < 0) return;
  r.object[idx] = h.object;
  const Object& obj = s.objects[size_t(h.object)];
  const Reference& ref = *shading[size_t(h.object)];
  const Material& m = ref.material();
  Vec3 p = eye + dir * h.hit.t;
  Vec3 v = -dir;
  ShadingFrame f = shading_frame(obj, ref, tangents[size_t(h.object)], p, h.hit, v);
  RGB L = ref.emitted(f.textured, s.ambient, dot(f.coat_n, v));  // the coat's normal: the emission lies under it
  bool grazing = f.grazing || h.fragile;
  uint8_t seen = dot(f.n, v) > 0 ? Render::kFacesCamera : 0;
  for (const auto& light : s.lights) {
    Vec3 l;
    double d;
    light.toward(p, l, d);
    double factor = ref.light_factor(light, l, d);
    // The object's own normal decides whether the light is above the surface (the surface
    // shadows itself below it, on every renderer); the lobes read the mapped one.
    if (!(factor > 0) || dot(f.n, l) <= 0) {
      grazing = grazing || (m.normal_map && factor > 0 && dot(f.n, l) > -kNormalMapHorizon && dot(f.shading_n, l) > 0);
      continue;
    }
    if (m.normal_map && dot(f.n, l) < kNormalMapHorizon && dot(f.shading_n, l) > 0) grazing = true;
    if (blocked(s, bvh, cut, h.object, h.hit.triangle, p, l, d, offset, close, grazing)) continue;
    seen |= Render::kReceivesLight;
    ShadingInputs in = shading_inputs(f.shading_n, l, v, f.t, f.coat_n, f.w);
    in.textured = f.textured.textured;
    RGB rho = ref.reflectance(in);
    for (int c = 0; c < 3; ++c) L[c] += factor * light.color[c] * rho[c];
  }
  r.grazing[idx] = grazing;
  r.seen[idx] = seen;
  for (int c = 0; c < 3; ++c) r.normal[idx * 3 + size_t(c)] = float(f.n[c]);
  float* px = r.image.at(x, y);
  for (int c = 0; c < 3; ++c) px[c] = float(L[c]);
}

Render render(const Material* fallback, const Scene& s, int width, int height, int threads) {
  // One reference per distinct material; object i uses shading[i].
  std::vector<std::unique_ptr<Reference>> refs;
  std::vector<const Reference*> shading(s.objects.size());
  std::map<const Material*, const Reference*> made;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material* m = &s.material_of(i, fallback);
    if (!made.count(m)) {
      refs.push_back(std::make_unique<Reference>(*m));
      made[m] = refs.back().get();
    }
    shading[i] = made[m];
  }
  Cutouts cut(s.objects.size(), nullptr);
  for (size_t i = 0; i < s.objects.size(); ++i)
    if (shading[i]->material().masked()) cut[i] = &shading[i]->material();
  // The normal-mapped meshes' tangents, once per render.
  std::vector<CornerTangents> tangents(s.objects.size());
  for (size_t i = 0; i < s.objects.size(); ++i)
    if (const auto set = shading[i]->material().frame_uv(); set && s.objects[i].type == Object::Type::Mesh)
      tangents[i] = mesh_tangents(*s.objects[i].mesh, *set);
  Render r;
  r.image = Image(width, height);
  r.object.assign(size_t(width) * size_t(height), -1);
  r.grazing.assign(size_t(width) * size_t(height), 0);
  r.seen.assign(size_t(width) * size_t(height), 0);
  r.normal.assign(size_t(width) * size_t(height) * 3, 0.0f);
  const double offset = kShadowRayOffset * scene_scale(s);
  const double close = std::max(kCloseBlock, kGrazing * scene_scale(s));
  const ObjectBvh bvh = object_bvh(s, true);
  // Rows on every core (or `threads`): each pixel is its own, so any split gives the same image.
  parallel_for(size_t(std::max(height, 0)), unsigned(std::max(threads, 0)), [&](size_t y) {
    for (int x = 0; x < width; ++x) shade_pixel(s, bvh, cut, shading, tangents, offset, close, x, int(y), r);
  });
  return r;
}

}  // namespace

Render render_reference(const Material& m, const Scene& s, int width, int height, int threads) {
  return render(&m, s, width, height, threads);
}

Render render_reference(const Scene& s, int width, int height, int threads) {
  return render(nullptr, s, width, height, threads);
}

}  // namespace facet
