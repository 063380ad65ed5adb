// Smooth test meshes of any size (shapes.h).
#include "scene/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include <fmt/format.h>

namespace facet {

namespace {


// Adds vertex p, or returns the one already within 1e-9 of it (shared edges are
// computed from both of their faces).
class Welder {
 public:
  explicit Welder(Mesh& m) : m_(m) {}
  uint32_t add(const Vec3& p) {
    auto key = std::make_tuple(std::llround(p.x * 1e9), std::llround(p.y * 1e9), std::llround(p.z * 1e9));
    auto [it, inserted] = index_.emplace(key, uint32_t(m_.positions.size()));
    if (inserted) m_.positions.push_back(p);
    return it->second;
  }

 private:
  Mesh& m_;
  std::map<std::tuple<long long, long long, long long>, uint32_t> index_;
};

void quad(Mesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {  // a b / d c, counter-clockwise
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

void smooth_normals(Mesh& m) {
  m.normals.assign(m.positions.size(), Vec3(0, 0, 0));
  for (const auto& t : m.triangles) {
    Vec3 g = cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    for (uint32_t k : t) m.normals[k] = m.normals[k] + g;
  }
  for (auto& n : m.normals) n = length(n) > 0 ? normalize(n) : Vec3(0, 1, 0);
}

Mesh icosphere(int k, const Vec3& center, double radius) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  const std::array<Vec3, 12> v = {Vec3(-1, g, 0), Vec3(1, g, 0), Vec3(-1, -g, 0), Vec3(1, -g, 0),
                                  Vec3(0, -1, g), Vec3(0, 1, g), Vec3(0, -1, -g), Vec3(0, 1, -g),
                                  Vec3(g, 0, -1), Vec3(g, 0, 1), Vec3(-g, 0, -1), Vec3(-g, 0, 1)};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  Mesh m;
  Welder weld(m);
  for (const auto& f : faces) {
    const Vec3 a = v[size_t(f[0])], b = v[size_t(f[1])], c = v[size_t(f[2])];
    // Row i of the face's grid has i + 1 points between a + (b − a)i/k and a + (c − a)i/k.
    std::vector<std::vector<uint32_t>> row(size_t(k) + 1);
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j <= i; ++j) {
        Vec3 p = a + (b - a) * (double(i - j) / k) + (c - a) * (double(j) / k);
        row[size_t(i)].push_back(weld.add(center + normalize(p) * radius));
      }
    for (size_t i = 0; i < size_t(k); ++i)
      for (size_t j = 0; j <= i; ++j) {
        m.triangles.push_back({row[i][j], row[i + 1][j], row[i + 1][j + 1]});
        if (j < i) m.triangles.push_back({row[i][j], row[i + 1][j + 1], row[i][j + 1]});
      }
  }
  smooth_normals(m);
  return m;
}

Mesh torus(int around, int across, const Vec3& center, double major, double minor) {
  Mesh m;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      double u = 2 * kPi * i / around, w = 2 * kPi * j / across;
      Vec3 ring(std::cos(u), 0, -std::sin(u));
      m.positions.push_back(center + ring * (major + minor * std::cos(w)) + Vec3(0, minor * std::sin(w), 0));
    }
  auto at = [&](int i, int j) { return uint32_t((i % around) * across + (j % across)); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  smooth_normals(m);
  return m;
}

Mesh creased_box(int n, const Vec3& center, double half, double bump) {
  Mesh m;
  // Each face: its normal and two in-plane axes with axis1 × axis2 = normal.
  const std::array<std::array<Vec3, 3>, 6> frames = {{{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                                                      {Vec3(-1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)},
                                                      {Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 0)},
                                                      {Vec3(0, -1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)},
                                                      {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                                      {Vec3(0, 0, -1), Vec3(0, 1, 0), Vec3(1, 0, 0)}}};
  for (const auto& [normal, s, t] : frames) {
    const uint32_t base = uint32_t(m.positions.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        double a = 2.0 * i / n - 1, b = 2.0 * j / n - 1;
        double h = bump * (1 - a * a) * (1 - b * b) * std::cos(3 * kPi * a) * std::cos(3 * kPi * b);
        m.positions.push_back(center + (normal * (1 + h) + s * a + t * b) * half);
      }
    auto at = [&](int i, int j) { return base + uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  smooth_normals(m);
  return m;
}

Scene mesh_bench_scene(size_t triangles) {
  const double third = double(triangles) / 3;
  Scene s;
  s.name = "mesh_bench";
  s.source = "built-in";
  s.camera.position = Vec3(0, 2.2, 7.5);
  s.camera.look_at = Vec3(0, -0.1, 0);
  s.camera.fov = 36;
  auto add = [&](const std::string& name, Mesh m) {
    m.build_bvh();
    Object o;
    o.type = Object::Type::Mesh;
    o.name = name;
    o.mesh = std::make_shared<const Mesh>(std::move(m));
    s.objects.push_back(o);
  };
  add("icosphere", icosphere(std::max(1, int(std::lround(std::sqrt(third / 20)))), Vec3(-2.6, 0, 0), 1));
  const int across = std::max(3, int(std::lround(std::sqrt(third / 4))));
  add("torus", torus(2 * across, across, Vec3(0, 0, 0), 0.85, 0.35));
  add("creased_box", creased_box(std::max(1, int(std::lround(std::sqrt(third / 12)))), Vec3(2.6, 0, 0), 0.8, 0.06));
  Light l;
  l.type = Light::Type::Point;
  l.position = Vec3(-3, 6, 6);
  l.color = {60, 58, 55};
  l.attenuation.law = Attenuation::Law::InverseSquare;
  s.lights.push_back(l);
  return s;
}

namespace {

// Object k of many_objects_scene's grid (k ≥ 1), in its cell centred at (x, 0, z).
Object grid_object(size_t k, double x, double z) {
  Object o;
  o.name = "object" + std::to_string(k);
  // A size between 0.22 and 0.32 that varies from cell to cell (the golden ratio's fraction).
  const double f = double(k) * 0.6180339887;
  const double size = 0.22 + 0.1 * (f - std::floor(f));
  if (k % 10 == 3) {
    static const std::array<Mesh (*)(const Vec3&, double), 3> kinds = {
        [](const Vec3& c, double s) { return icosphere(2, c, s); },
        [](const Vec3& c, double s) { return torus(12, 6, c, 0.7 * s, 0.3 * s); },
        [](const Vec3& c, double s) { return creased_box(2, c, 0.8 * s, 0.08); }};
    Mesh m = kinds[(k / 10) % 3](Vec3(x, size + 0.05, z), size);
    m.build_bvh();
    o.type = Object::Type::Mesh;
    o.mesh = std::make_shared<const Mesh>(std::move(m));
  } else if (k % 10 == 7) {
    o.type = Object::Type::Plane;
    o.point = Vec3(x, 0.45, z);
    o.normal = normalize(Vec3(0.3 * std::cos(f), 1, 0.3 * std::sin(f)));
    o.size = size;
  } else {
    o.center = Vec3(x, size + 0.05, z);
    o.radius = size;
  }
  return o;
}

// Light j of n, above the grid of half-width `half`: point, spot, directional in turn.
Light grid_light(size_t j, size_t n, double half) {
  Light l;
  const double angle = double(j) * 2.399963229728653;  // the golden angle: an even spread
  const double r = 0.9 * half * std::sqrt((double(j) + 0.5) / double(n)), height = 2.5 + double(j % 5) * 0.4;
  const double scale = 3.0 / double(n);
  l.color = {scale * (0.8 + 0.2 * std::cos(angle)), scale * 0.9, scale * (0.8 + 0.2 * std::sin(angle))};
  l.position = Vec3(r * std::cos(angle), height, r * std::sin(angle));
  static const std::array<Attenuation::Law, 3> laws = {Attenuation::Law::None, Attenuation::Law::InverseSquare,
                                                       Attenuation::Law::Polynomial};
  if (j % 3 == 2) {
    l.type = Light::Type::Directional;
    l.direction = normalize(Vec3(0.5 * std::sin(angle), -1, 0.5 * std::cos(angle)));
    return l;
  }
  l.attenuation.law = laws[(j / 3) % 3];
  // Brighter where the law dims: about as bright on the floor below as without attenuation.
  double gain = 1;
  if (l.attenuation.law == Attenuation::Law::InverseSquare) gain = height * height;
  if (l.attenuation.law == Attenuation::Law::Polynomial) {  // 1 / (1 + 0.1 d²): a POV-Ray fade too
    l.attenuation.quadratic = 0.1;
    gain = 2;
  }
  for (double& c : l.color) c *= gain;
  if (j % 3 == 1) {
    l.type = Light::Type::Spot;
    l.direction = normalize(Vec3(-0.3 * std::cos(angle), -1, -0.3 * std::sin(angle)));
    l.cutoff = 50;
    l.exponent = 2;
  }
  return l;
}

}  // namespace

Scene many_objects_scene(size_t objects, size_t lights, const std::vector<Material>& materials) {
  Scene s;
  s.name = fmt::format("many_{}x{}", objects, lights);
  s.source = "built-in";
  for (const Material& m : materials) s.materials[m.name] = m;
  const size_t cells = objects > 1 ? objects - 1 : 0;
  const size_t side = size_t(std::ceil(std::sqrt(double(cells))));
  const double half = 0.5 * double(std::max<size_t>(side, 1));
  auto shade = [&](Object& o, size_t k) {
    if (!materials.empty()) o.material = materials[k % materials.size()].name;
  };
  if (objects > 0) {
    Object floor;
    floor.type = Object::Type::Plane;
    floor.name = "floor";
    floor.point = Vec3(0, 0, 0);
    floor.normal = Vec3(0, 1, 0);
    floor.size = half + 0.5;
    shade(floor, 0);
    s.objects.push_back(floor);
  }
  for (size_t k = 1; k <= cells; ++k) {
    const size_t cell = k - 1;
    Object o = grid_object(k, double(cell % side) + 0.5 - half, double(cell / side) + 0.5 - half);
    shade(o, k);
    s.objects.push_back(std::move(o));
  }
  for (size_t j = 0; j < lights; ++j) s.lights.push_back(grid_light(j, lights, half));
  s.ambient = {0.02, 0.02, 0.02};
  s.camera.position = Vec3(0, 0.75 * half + 1.5, 1.05 * half + 2.5);
  s.camera.look_at = Vec3(0, 0, 0.1 * half);
  s.camera.fov = 50;
  return s;
}

}  // namespace facet
