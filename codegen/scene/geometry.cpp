// Ray intersection for facet's objects: analytic spheres and squares, and
// triangle meshes through a bounding volume hierarchy.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "scene/bvh.h"
#include "scene/scene.h"

namespace facet {

namespace {

Vec3 vmin(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 vmax(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection"; two-sided.
bool ray_triangle(const Vec3& o, const Vec3& d, const Vec3& p0, const Vec3& p1, const Vec3& p2, double& t, double& u,
                  double& v) {
  Vec3 e1 = p1 - p0, e2 = p2 - p0;
  Vec3 pv = cross(d, e2);
  double det = dot(e1, pv);
  if (det == 0) return false;
  double inv = 1.0 / det;
  Vec3 tv = o - p0;
  u = dot(tv, pv) * inv;
  if (u < 0 || u > 1) return false;
  Vec3 qv = cross(tv, e1);
  v = dot(d, qv) * inv;
  if (v < 0 || u + v > 1) return false;
  t = dot(e2, qv) * inv;
  return true;
}

}  // namespace

void Mesh::build_bvh() {
  std::vector<Vec3> lo(triangles.size()), hi(triangles.size()), centroid(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto& tri = triangles[i];
    lo[i] = vmin(vmin(positions[tri[0]], positions[tri[1]]), positions[tri[2]]);
    hi[i] = vmax(vmax(positions[tri[0]], positions[tri[1]]), positions[tri[2]]);
    centroid[i] = (positions[tri[0]] + positions[tri[1]] + positions[tri[2]]) / 3.0;
  }
  facet::build_bvh(lo, hi, centroid, 4, nodes, order);
}

void Mesh::candidates(const Vec3& o, const Vec3& d, double t_max, double margin,
                      const std::function<void(int)>& visit) const {
  if (nodes.empty()) return;
  Vec3 inv(1 / d.x, 1 / d.y, 1 / d.z);
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes[size_t(stack[--top])];
    Vec3 grow = (n.hi - n.lo) * margin + Vec3(1e-12, 1e-12, 1e-12);
    if (!ray_box(o, inv, n.lo - grow, n.hi + grow, t_max)) continue;
    if (n.count > 0) {
      for (uint32_t i = n.start; i < n.start + n.count; ++i) visit(int(order[i]));
    } else {
      stack[top++] = n.right;
      stack[top++] = int(&n - nodes.data()) + 1;
      if (top >= 63) throw std::logic_error("facet: mesh hierarchy deeper than 63");
    }
  }
}

Vec3 Mesh::normal(int t, double u, double v) const {
  const auto& tri = triangles[size_t(t)];
  return normalize(normals[tri[0]] * (1 - u - v) + normals[tri[1]] * u + normals[tri[2]] * v);
}

Hit Object::hit(const Vec3& o, const Vec3& d, double t_min, int skip) const {
  Hit h;
  if (type == Type::Sphere) {
    Vec3 oc = o - center;
    double b = dot(oc, d);
    double c = dot(oc, oc) - radius * radius;
    double disc = b * b - c;
    if (disc < 0) return h;
    double s = std::sqrt(disc);
    // The nearer root, computed without cancellation.
    double q = b > 0 ? -(b + s) : -(b - s);
    double t0 = q, t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_min) h.t = t0;
    else if (t1 > t_min) h.t = t1;
    return h;
  }
  if (type == Type::Plane) {
    double den = dot(d, normal);
    if (den == 0) return h;
    double t = dot(point - o, normal) / den;
    if (!(t > t_min)) return h;
    Vec3 p = o + d * t - point, u, v;
    plane_axes(u, v);
    if (std::fabs(dot(p, u)) > size || std::fabs(dot(p, v)) > size) return h;
    h.t = t;
    return h;
  }
  const Mesh& m = *mesh;
  if (m.nodes.empty()) return h;
  Vec3 inv(1 / d.x, 1 / d.y, 1 / d.z);
  double best = INFINITY;
  int stack[64], top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Mesh::Node& n = m.nodes[size_t(stack[--top])];
    if (!ray_box(o, inv, n.lo, n.hi, best)) continue;
    if (n.count > 0) {
      for (uint32_t i = n.start; i < n.start + n.count; ++i) {
        int tri = int(m.order[i]);
        if (tri == skip) continue;
        const auto& k = m.triangles[size_t(tri)];
        double t, u, v;
        if (ray_triangle(o, d, m.positions[k[0]], m.positions[k[1]], m.positions[k[2]], t, u, v) && t > t_min &&
            t < best) {
          best = t;
          h = {t, tri, u, v};
        }
      }
    } else {
      int self = int(&n - m.nodes.data());
      stack[top++] = n.right;
      stack[top++] = self + 1;
      if (top >= 63) throw std::logic_error("facet: mesh hierarchy deeper than 63");
    }
  }
  return h;
}

Vec3 Object::normal_at(const Vec3& p, const Hit& h) const {
  switch (type) {
    case Type::Sphere: return normalize(p - center);
    case Type::Plane: return normal;
    case Type::Mesh: return mesh->normal(h.triangle, h.u, h.v);
  }
  return normal;
}

std::array<std::array<double, 2>, 2> Object::uv_at(const Vec3& p, const Hit& h) const {
  std::array<double, 2> st{0, 0};
  switch (type) {
    case Type::Sphere: {
      // Longitude from +z towards +x, latitude from the +y pole: v = 0 at the top.
      Vec3 d = (p - center) / radius;
      st = {0.5 + std::atan2(d.x, d.z) / (2 * M_PI), std::acos(std::clamp(d.y, -1.0, 1.0)) / M_PI};
      return {st, st};
    }
    case Type::Plane: {
      // The square's own axes: u along the first, v down the second, [0, 1]² edge to edge.
      Vec3 a, b;
      plane_axes(a, b);
      Vec3 q = p - point;
      st = {0.5 + dot(q, a) / (2 * size), 0.5 - dot(q, b) / (2 * size)};
      return {st, st};
    }
    case Type::Mesh: {
      std::array<std::array<double, 2>, 2> out{};
      for (size_t set = 0; set < 2; ++set) {
        const auto& tc = mesh->texcoords[set];
        if (tc.empty()) continue;
        const auto& tri = mesh->triangles[size_t(h.triangle)];
        const double w0 = 1 - h.u - h.v;
        for (size_t k = 0; k < 2; ++k)
          out[set][k] = w0 * tc[tri[0]][k] + h.u * tc[tri[1]][k] + h.v * tc[tri[2]][k];
      }
      return out;
    }
  }
  return {st, st};
}

std::array<double, 4> Object::color_at(const Hit& h) const {
  if (type != Type::Mesh || mesh->colors.empty()) return {1, 1, 1, 1};
  const auto& c = mesh->colors;
  const auto& tri = mesh->triangles[size_t(h.triangle)];
  const double w0 = 1 - h.u - h.v;
  std::array<double, 4> out{};
  for (size_t k = 0; k < 4; ++k) out[k] = w0 * c[tri[0]][k] + h.u * c[tri[1]][k] + h.v * c[tri[2]][k];
  return out;
}

bool Object::tangent_at(const Vec3& p, const Hit&, Vec3& t, double& w) const {
  w = 1;
  switch (type) {
    case Type::Sphere: {
      // u grows with the longitude atan2(d_x, d_z): ∂d/∂u ∝ (d_z, 0, −d_x). v grows
      // towards −y, so B = n × t (towards +y, up the picture) and w = +1.
      const Vec3 d = p - center;
      t = normalize(Vec3(d.z, 0, -d.x));
      return true;
    }
    case Type::Plane: {
      // u grows along a, v down b = n × a: t = a, B = n × a = b, w = +1.
      Vec3 b;
      plane_axes(t, b);
      return true;
    }
    case Type::Mesh: return false;
  }
  return false;
}

void Object::bounds(Vec3& c, double& r) const {
  switch (type) {
    case Type::Sphere:
      c = center;
      r = radius;
      return;
    case Type::Plane:
      c = point;
      r = size * std::sqrt(2.0);
      return;
    case Type::Mesh: {
      Vec3 lo = mesh->nodes.empty() ? Vec3() : mesh->nodes[0].lo, hi = mesh->nodes.empty() ? Vec3() : mesh->nodes[0].hi;
      c = (lo + hi) * 0.5;
      r = length(hi - lo) * 0.5;
      return;
    }
  }
}

}  // namespace facet
