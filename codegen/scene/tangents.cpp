#include "scene/tangents.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace facet {

namespace {

// Vertices with equal position, normal and coordinates, numbered as one (the first's index).
std::vector<uint32_t> weld(const Mesh& m, int set) {
  std::map<std::array<double, 8>, uint32_t> first;
  std::vector<uint32_t> out(m.positions.size());
  const auto& tc = m.texcoords[size_t(set)];
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 &p = m.positions[i], &n = m.normals[i];
    std::array<double, 8> key = {p.x, p.y, p.z, n.x, n.y, n.z, tc[i][0], tc[i][1]};
    out[i] = first.emplace(key, uint32_t(i)).first->second;
  }
  return out;
}

struct Face {
  Vec3 os;                // the unit ∂p/∂s, or 0
  bool preserves = true;  // the (s, t) triangle, t up, is counter-clockwise
};

Face face_of(const Mesh& m, int set, const std::array<uint32_t, 3>& k) {
  const auto& tc = m.texcoords[size_t(set)];
  auto st = [&](uint32_t v) { return std::array<double, 2>{tc[v][0], 1 - tc[v][1]}; };  // t up the picture
  const auto t1 = st(k[0]), t2 = st(k[1]), t3 = st(k[2]);
  const double t21x = t2[0] - t1[0], t21y = t2[1] - t1[1], t31x = t3[0] - t1[0], t31y = t3[1] - t1[1];
  const Vec3 d1 = m.positions[k[1]] - m.positions[k[0]], d2 = m.positions[k[2]] - m.positions[k[0]];
  const double area = t21x * t31y - t21y * t31x;  // twice the signed (s, t) area
  Face f;
  f.preserves = area > 0;
  const Vec3 os = d1 * t31y - d2 * t21y;  // area · ∂p/∂s
  if (area != 0 && length(os) > 0) f.os = os * ((f.preserves ? 1.0 : -1.0) / length(os));
  return f;
}

Vec3 unit_in_plane(const Vec3& v, const Vec3& n) {
  const Vec3 p = v - n * dot(n, v);
  const double len = length(p);
  return len > 0 ? p / len : Vec3();
}

// The corners of each welded vertex joined through shared edges of triangles of the same
// orientation: group[3·i + k], numbered from 0.
std::vector<int> corner_groups(const Mesh& m, const std::vector<uint32_t>& weld, const std::vector<Face>& faces) {
  const size_t corners = m.triangles.size() * 3;
  auto vertex = [&](size_t c) { return weld[m.triangles[c / 3][c % 3]]; };
  // Each directed edge (a, b) of a triangle: its corner at a. A neighbour across (a, b) holds (b, a).
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
  for (size_t c = 0; c < corners; ++c) edges[{vertex(c), vertex(c - c % 3 + (c + 1) % 3)}].push_back(c);
  std::vector<int> group(corners, -1);
  int next = 0;
  for (size_t start = 0; start < corners; ++start) {
    if (group[start] >= 0) continue;
    std::vector<size_t> stack = {start};
    group[start] = next;
    while (!stack.empty()) {
      const size_t c = stack.back();
      stack.pop_back();
      const size_t base = c - c % 3;
      const uint32_t v = vertex(c), after = vertex(base + (c + 1) % 3), before = vertex(base + (c + 2) % 3);
      // Across (v, after) a neighbour holds (after, v); across (before, v) it holds (v, before).
      auto join = [&](std::pair<uint32_t, uint32_t> e, bool at_second) {
        auto it = edges.find(e);
        if (it == edges.end()) return;
        for (size_t d : it->second) {
          const size_t own = at_second ? d - d % 3 + (d + 1) % 3 : d;  // the neighbour's corner at v
          if (group[own] >= 0 || faces[own / 3].preserves != faces[c / 3].preserves) continue;
          group[own] = next;
          stack.push_back(own);
        }
      };
      join({after, v}, true);
      join({v, before}, false);
    }
    ++next;
  }
  return group;
}

}  // namespace

Vec3 tangent_rule(const Vec3& n, const Vec3& axis) {
  Vec3 t = cross(normalize(axis), n);
  if (length(t) < kEpsilon) t = cross(Vec3(1, 0, 0), n);
  return normalize(t);
}

std::vector<std::array<double, 4>> mikktspace_tangents(const Mesh& m, int set) {
  const std::vector<uint32_t> welded = weld(m, set);
  std::vector<Face> faces;
  for (const auto& k : m.triangles) faces.push_back(face_of(m, set, k));
  const std::vector<int> group = corner_groups(m, welded, faces);
  const size_t corners = m.triangles.size() * 3;
  std::vector<Vec3> sum(corners);  // per group (a group is numbered below the corner count)
  for (size_t c = 0; c < corners; ++c) {
    const auto& k = m.triangles[c / 3];
    const size_t i = c % 3;
    const Vec3 n = normalize(m.normals[k[i]]), p = m.positions[k[i]];
    const Vec3 e1 = unit_in_plane(m.positions[k[(i + 2) % 3]] - p, n), e2 = unit_in_plane(m.positions[k[(i + 1) % 3]] - p, n);
    const double angle = std::acos(std::clamp(dot(e1, e2), -1.0, 1.0));
    sum[size_t(group[c])] = sum[size_t(group[c])] + unit_in_plane(faces[c / 3].os, n) * angle;
  }
  std::vector<std::array<double, 4>> out(corners);
  for (size_t c = 0; c < corners; ++c) {
    const Vec3& s = sum[size_t(group[c])];
    const Vec3 t = length(s) > 0 ? s / length(s) : Vec3();
    out[c] = {t.x, t.y, t.z, faces[c / 3].preserves ? 1.0 : -1.0};
  }
  return out;
}

std::vector<std::array<double, 4>> mesh_tangents(const Mesh& m, int set) {
  if (m.tangents.empty()) return mikktspace_tangents(m, set);
  std::vector<std::array<double, 4>> out;
  out.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
    for (uint32_t v : t) out.push_back(m.tangents[v]);
  return out;
}

void blend_tangent(const Mesh&, const std::vector<std::array<double, 4>>& corners, const Hit& h, Vec3& t, double& w) {
  const size_t c = size_t(h.triangle) * 3;
  const double b[3] = {1 - h.u - h.v, h.u, h.v};
  double sw = 0;
  t = Vec3();
  for (size_t k = 0; k < 3; ++k) {
    const auto& x = corners[c + k];
    t = t + Vec3(x[0], x[1], x[2]) * b[k];
    sw += b[k] * x[3];
  }
  w = sw >= 0 ? 1 : -1;
}

}  // namespace facet
