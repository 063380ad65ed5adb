// Bounding volume hierarchies: the builder meshes and scenes share, and the top level over
// a scene's objects.
#include "scene/bvh.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace facet {

namespace {

Vec3 vmin(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 vmax(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// How much of its size an object's box grows by (object_box): ten times the reference's
// grazing distance, kGrazing = 1e-4 (a mesh's own hierarchy grows its boxes by 2·kGrazing).
constexpr double kBoxMargin = 1e-3;

}  // namespace

bool ray_box(const Vec3& o, const Vec3& inv_d, const Vec3& lo, const Vec3& hi, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    double near = (lo[a] - o[a]) * inv_d[a], far = (hi[a] - o[a]) * inv_d[a];
    if (near > far) std::swap(near, far);
    if (std::isnan(near)) near = -INFINITY;  // 0 · ∞ on a slab plane
    if (std::isnan(far)) far = INFINITY;
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

void build_bvh(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, const std::vector<Vec3>& centroid,
               uint32_t leaf, std::vector<Mesh::Node>& nodes, std::vector<uint32_t>& order) {
  nodes.clear();
  order.resize(lo.size());
  std::iota(order.begin(), order.end(), 0u);
  // Median split on the longest axis of the centroids.
  std::function<void(uint32_t, uint32_t)> build = [&](uint32_t start, uint32_t end) {
    size_t id = nodes.size();
    nodes.push_back({});
    Vec3 box_lo(INFINITY, INFINITY, INFINITY), box_hi(-INFINITY, -INFINITY, -INFINITY);
    Vec3 clo = box_lo, chi = box_hi;
    for (uint32_t i = start; i < end; ++i) {
      box_lo = vmin(box_lo, lo[order[i]]);
      box_hi = vmax(box_hi, hi[order[i]]);
      clo = vmin(clo, centroid[order[i]]);
      chi = vmax(chi, centroid[order[i]]);
    }
    nodes[id].lo = box_lo;
    nodes[id].hi = box_hi;
    if (end - start <= leaf) {
      nodes[id].start = start;
      nodes[id].count = end - start;
      return;
    }
    Vec3 ext = chi - clo;
    int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    uint32_t mid = start + (end - start) / 2;
    std::nth_element(order.begin() + start, order.begin() + mid, order.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
    build(start, mid);
    nodes[id].right = int32_t(nodes.size());
    build(mid, end);
  };
  if (!lo.empty()) build(0, uint32_t(lo.size()));
}

void object_box(const Object& o, Vec3& lo, Vec3& hi, bool grazing) {
  switch (o.type) {
    case Object::Type::Sphere: {
      const double r = (grazing ? 1.5 : 1 + kBoxMargin) * o.radius;
      lo = o.center - Vec3(r, r, r);
      hi = o.center + Vec3(r, r, r);
      return;
    }
    case Object::Type::Plane: {
      Vec3 u, v;
      o.plane_axes(u, v);
      const Vec3 half(std::fabs(u.x) + std::fabs(v.x), std::fabs(u.y) + std::fabs(v.y), std::fabs(u.z) + std::fabs(v.z));
      const Vec3 grow = half * o.size + Vec3(1, 1, 1) * (kBoxMargin * o.size);
      lo = o.point - grow;
      hi = o.point + grow;
      return;
    }
    case Object::Type::Mesh: {
      if (o.mesh->nodes.empty()) {  // no triangles: a box nothing enters
        lo = Vec3(INFINITY, INFINITY, INFINITY);
        hi = -lo;
        return;
      }
      const Mesh::Node& root = o.mesh->nodes[0];
      const Vec3 ext = root.hi - root.lo;
      const double g = kBoxMargin * std::max({ext.x, ext.y, ext.z}) + 1e-12;
      lo = root.lo - Vec3(g, g, g);
      hi = root.hi + Vec3(g, g, g);
      return;
    }
  }
}

ObjectBvh object_bvh(const Scene& s, bool grazing) {
  const size_t n = s.objects.size();
  std::vector<Vec3> lo(n), hi(n), centroid(n);
  for (size_t i = 0; i < n; ++i) {
    object_box(s.objects[i], lo[i], hi[i], grazing);
    // An empty mesh's box is inverted: its centroid is any point (the origin).
    centroid[i] = lo[i].x <= hi[i].x ? (lo[i] + hi[i]) * 0.5 : Vec3();
  }
  ObjectBvh b;
  build_bvh(lo, hi, centroid, ObjectBvh::kObjectsPerLeaf, b.nodes, b.order);
  return b;
}

}  // namespace facet
