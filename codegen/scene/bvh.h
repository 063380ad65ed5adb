// facet — bounding volume hierarchies: the one builder a mesh's triangles and a scene's
// objects share (median split on the longest axis of the centroids), and the top level over
// a scene's objects that the reference ray caster and the GL ray caster walk instead of
// every object for every ray (docs/many_objects.md measured why: a ray's time grew as the
// number of objects without it).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace facet {

// Nodes over items i with boxes [lo[i], hi[i]] and centroids centroid[i], depth first as
// Mesh::nodes (an inner node's left child follows it, `right` indexes the other; a leaf
// holds `count` items from `start` in `order`), at most `leaf` items a leaf.
void build_bvh(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, const std::vector<Vec3>& centroid,
               uint32_t leaf, std::vector<Mesh::Node>& nodes, std::vector<uint32_t>& order);

// Slab test: does the ray origin + t·dir (inv_dir = 1/dir) enter the box at some t in [0, t_max]?
bool ray_box(const Vec3& origin, const Vec3& inv_dir, const Vec3& lo, const Vec3& hi, double t_max);

// The box of an object that every ray meeting it enters, grown by 1e-3 of its size (room for
// float rounding); with `grazing`, grown so that it also holds every ray the reference counts as
// grazing it (reference/raycaster.h, kGrazing = 1e-4 relative): a sphere's by half its radius (a
// shadow ray's closest approach to it may lie up to a radius past the ray's end). A ray that
// misses the box changes nothing the reference (with `grazing`) or the GL ray caster (without:
// its rays only meet objects, and a tighter box is entered by fewer rays) computes for the object.
void object_box(const Object& o, Vec3& lo, Vec3& hi, bool grazing);

// The top level: a hierarchy over a scene's objects, leaves of up to kObjectsPerLeaf objects.
struct ObjectBvh {
  static constexpr uint32_t kObjectsPerLeaf = 2;
  std::vector<Mesh::Node> nodes;
  std::vector<uint32_t> order;  // the objects' indices in leaf order

  // Calls visit(object) for each object whose box the ray origin + t·dir enters at some t in
  // [0, t_max()] (asked again at every node: a nearest-hit search shrinks it), until visit
  // returns false.
  template <class TMax, class Visit>
  void walk(const Vec3& origin, const Vec3& dir, TMax t_max, Visit visit) const;
};
ObjectBvh object_bvh(const Scene& s, bool grazing);

template <class TMax, class Visit>
void ObjectBvh::walk(const Vec3& o, const Vec3& d, TMax t_max, Visit visit) const {
  if (nodes.empty()) return;
  const Vec3 inv(1 / d.x, 1 / d.y, 1 / d.z);
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Mesh::Node& n = nodes[stack[--top]];
    if (!ray_box(o, inv, n.lo, n.hi, t_max())) continue;
    if (n.count > 0) {
      for (uint32_t i = n.start; i < n.start + n.count; ++i)
        if (!visit(order[i])) return;
    } else {
      // A median split is balanced: depth log2(objects), far below the stack's 64.
      stack[top++] = uint32_t(n.right);
      stack[top++] = uint32_t(&n - nodes.data()) + 1;
    }
  }
}

}  // namespace facet
