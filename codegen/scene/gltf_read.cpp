// facet's reading of glTF triangles (gltf_read.h); tinygltf's own code is compiled in gltf.cpp.
#include "scene/gltf_read.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "core/diagnostics.h"
#include "core/io.h"

namespace facet::gltf_detail {

using nlohmann::json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------- matrices

Mat4 Mat4::operator*(const Mat4& b) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += (*this)(i, k) * b(k, j);
      r(i, j) = s;
    }
  return r;
}

Vec3 Mat4::point(const Vec3& p) const {
  return {(*this)(0, 0) * p.x + (*this)(0, 1) * p.y + (*this)(0, 2) * p.z + (*this)(0, 3),
          (*this)(1, 0) * p.x + (*this)(1, 1) * p.y + (*this)(1, 2) * p.z + (*this)(1, 3),
          (*this)(2, 0) * p.x + (*this)(2, 1) * p.y + (*this)(2, 2) * p.z + (*this)(2, 3)};
}

Vec3 Mat4::direction(const Vec3& d) const {
  return {(*this)(0, 0) * d.x + (*this)(0, 1) * d.y + (*this)(0, 2) * d.z,
          (*this)(1, 0) * d.x + (*this)(1, 1) * d.y + (*this)(1, 2) * d.z,
          (*this)(2, 0) * d.x + (*this)(2, 1) * d.y + (*this)(2, 2) * d.z};
}

double Mat4::det3() const {
  const Mat4& a = *this;
  return a(0, 0) * (a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1)) - a(0, 1) * (a(1, 0) * a(2, 2) - a(1, 2) * a(2, 0)) +
         a(0, 2) * (a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
}

Vec3 Mat4::normal(const Vec3& n) const {
  const Mat4& a = *this;
  Vec3 c0(a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2), a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
  Vec3 c1(a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0), a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1));
  Vec3 c2(a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2), a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0));
  Vec3 r = c0 * n.x + c1 * n.y + c2 * n.z;
  return normalize(det3() < 0 ? -r : r);
}

Mat4 local_matrix(const tinygltf::Node& n) {
  Mat4 m;
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m.m[i] = n.matrix[size_t(i)];
    return m;
  }
  Mat4 t, r, s;
  if (n.translation.size() == 3) t(0, 3) = n.translation[0], t(1, 3) = n.translation[1], t(2, 3) = n.translation[2];
  if (n.rotation.size() == 4) {
    double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r(0, 0) = 1 - 2 * (y * y + z * z), r(0, 1) = 2 * (x * y - z * w), r(0, 2) = 2 * (x * z + y * w);
    r(1, 0) = 2 * (x * y + z * w), r(1, 1) = 1 - 2 * (x * x + z * z), r(1, 2) = 2 * (y * z - x * w);
    r(2, 0) = 2 * (x * z - y * w), r(2, 1) = 2 * (y * z + x * w), r(2, 2) = 1 - 2 * (x * x + y * y);
  }
  if (n.scale.size() == 3) s(0, 0) = n.scale[0], s(1, 1) = n.scale[1], s(2, 2) = n.scale[2];
  return t * r * s;
}

// ---------------------------------------------------------------- accessors

void Reader::fail(const std::string& path, const std::string& message) const {
  throw InputError({{file_, path, message, 0, 0}});
}

// The accessor's elements lie inside its buffer view, and the view inside its buffer:
//   accessor.byteOffset + stride·(count − 1) + element ≤ view.byteLength,
//   view.byteOffset + view.byteLength ≤ buffer size,
// checked without overflowing, before any element is read.
AccessorView Reader::view(int index, const std::string& path, int type) const {
  if (index < 0 || size_t(index) >= m_.accessors.size()) fail(path, fmt::format("names no accessor ({})", index));
  const auto& a = m_.accessors[size_t(index)];
  std::string apath = fmt::format("accessors[{}]", index);
  if (a.sparse.isSparse) fail(apath, "sparse accessors are not supported");
  if (a.bufferView < 0 || size_t(a.bufferView) >= m_.bufferViews.size()) fail(apath, "has no buffer view");
  const auto& v = m_.bufferViews[size_t(a.bufferView)];
  std::string vpath = fmt::format("bufferViews[{}]", a.bufferView);
  if (v.buffer < 0 || size_t(v.buffer) >= m_.buffers.size()) fail(vpath + ".buffer", "names no buffer");
  const size_t size = m_.buffers[size_t(v.buffer)].data.size();
  if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
    fail(vpath, fmt::format("bytes {} to {} lie past the end of buffer {} ({} bytes)", v.byteOffset,
                            uint64_t(v.byteOffset) + v.byteLength, v.buffer, size));
  if (a.type != type)
    fail(apath, type == TINYGLTF_TYPE_VEC3   ? "expected VEC3 of FLOAT"
                : type == TINYGLTF_TYPE_VEC2 ? "expected VEC2 (texture coordinates)"
                                             : "indices must be SCALAR");
  int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  if (component_size <= 0) fail(apath, "has an unknown componentType");
  const size_t elem = size_t(component_size) * size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
  AccessorView out{index, nullptr, a.count, v.byteStride ? v.byteStride : elem, a.componentType};
  if (out.stride < elem) fail(vpath + ".byteStride", "is smaller than one element");
  const size_t room = v.byteLength;
  bool inside = a.byteOffset <= room && (a.count == 0 || (elem <= room - a.byteOffset &&
                                                           (room - a.byteOffset - elem) / out.stride >= a.count - 1));
  if (!inside)
    fail(apath, fmt::format("its {} elements of {} bytes (stride {}) from byte {} need more than the {} bytes of "
                            "bufferViews[{}]",
                            thousands(a.count), elem, out.stride, a.byteOffset, thousands(room), a.bufferView));
  out.data = m_.buffers[size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
  return out;
}

AccessorView Reader::vec3(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_VEC3);
  if (a.component != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(fmt::format("accessors[{}]", index), "expected VEC3 of FLOAT");
  return a;
}

AccessorView Reader::vec2(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_VEC2);
  const bool normalized = m_.accessors[size_t(index)].normalized;
  if (a.component != TINYGLTF_COMPONENT_TYPE_FLOAT &&
      !(normalized && (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)))
    fail(fmt::format("accessors[{}]", index), "texture coordinates must be FLOAT or normalized unsigned bytes or shorts");
  return a;
}

std::array<double, 2> Reader::vec2_at(const AccessorView& a, size_t i) const {
  const unsigned char* e = a.data + i * a.stride;
  if (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return {e[0] / 255.0, e[1] / 255.0};
  if (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    uint16_t v[2];
    std::memcpy(v, e, sizeof v);
    return {v[0] / 65535.0, v[1] / 65535.0};
  }
  float f[2];
  std::memcpy(f, e, sizeof f);
  if (!std::isfinite(f[0]) || !std::isfinite(f[1]))
    fail(fmt::format("accessors[{}]", a.accessor), fmt::format("element {} is not finite", i));
  return {f[0], f[1]};
}

AccessorView Reader::vec4(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_VEC4);
  if (a.component != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(fmt::format("accessors[{}]", index), "expected VEC4 of FLOAT");
  return a;
}

std::array<double, 4> Reader::vec4_at(const AccessorView& a, size_t i) const {
  float f[4];
  std::memcpy(f, a.data + i * a.stride, sizeof f);
  for (float x : f)
    if (!std::isfinite(x)) fail(fmt::format("accessors[{}]", a.accessor), fmt::format("element {} is not finite", i));
  if (f[0] == 0 && f[1] == 0 && f[2] == 0)
    fail(fmt::format("accessors[{}]", a.accessor), fmt::format("element {}: a tangent of length 0 has no direction", i));
  return {f[0], f[1], f[2], f[3]};
}

AccessorView Reader::indices(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_SCALAR);
  if (a.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(fmt::format("accessors[{}]", index), "indices must be unsigned integers");
  return a;
}

Vec3 Reader::vec3_at(const AccessorView& a, size_t i) const {
  float f[3];
  std::memcpy(f, a.data + i * a.stride, sizeof f);
  if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
    fail(fmt::format("accessors[{}]", a.accessor), fmt::format("element {} is not finite", i));
  return Vec3(f[0], f[1], f[2]);
}

uint32_t Reader::index_at(const AccessorView& a, size_t i) {
  const unsigned char* e = a.data + i * a.stride;
  if (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *e;
  if (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    uint16_t v;
    std::memcpy(&v, e, 2);
    return v;
  }
  uint32_t v;
  std::memcpy(&v, e, 4);
  return v;
}

const std::vector<int>& Reader::parents() const {
  if (have_parents_) return parents_;
  parents_.assign(m_.nodes.size(), -1);
  for (size_t p = 0; p < m_.nodes.size(); ++p)
    for (int c : m_.nodes[p].children) {
      if (c < 0 || size_t(c) >= m_.nodes.size()) continue;  // named when the node is read
      int& slot = parents_[size_t(c)];
      slot = slot == -1 ? int(p) : kSeveral;
    }
  have_parents_ = true;
  return parents_;
}

Mat4 Reader::world_matrix(int ni) const {
  const std::vector<int>& up = parents();
  std::vector<int> chain;  // ni, its parent, …, the root
  for (int n = ni; n >= 0; n = up[size_t(n)]) {
    if (chain.size() > up.size())
      fail(fmt::format("nodes[{}]", ni), "its ancestors make a cycle (the node hierarchy must be a tree)");
    chain.push_back(n);
    if (up[size_t(n)] == kSeveral)
      fail(fmt::format("nodes[{}]", n), "is a child of several nodes; glTF allows a node one parent");
  }
  Mat4 world;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) world = world * local_matrix(m_.nodes[size_t(*it)]);
  return world;
}

// ---------------------------------------------------------------- primitives

bool is_triangles(const tinygltf::Primitive& prim) { return prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == -1; }

PrimitivePlan plan_primitive(const Reader& r, const tinygltf::Primitive& prim, const std::string& path,
                             const std::string& where) {
  PrimitivePlan p;
  p.prim = &prim;
  p.path = path;
  p.where = where;
  if (!is_triangles(prim)) r.fail(path + ".mode", fmt::format("{}; facet takes triangles (mode 4)", prim.mode));
  auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) r.fail(path + ".attributes", "has no POSITION");
  p.positions = r.vec3(pos->second, path + ".attributes.POSITION");
  auto nor = prim.attributes.find("NORMAL");
  p.has_normals = nor != prim.attributes.end();
  if (p.has_normals) {
    p.normals = r.vec3(nor->second, path + ".attributes.NORMAL");
    if (p.normals.count != p.positions.count)
      r.fail(path + ".attributes.NORMAL", "has a different count from POSITION");
  }
  for (size_t set = 0; set < 2; ++set) {
    const std::string key = "TEXCOORD_" + std::to_string(set);
    auto tc = prim.attributes.find(key);
    p.has_texcoords[set] = tc != prim.attributes.end();
    if (!p.has_texcoords[set]) continue;
    p.texcoords[set] = r.vec2(tc->second, path + ".attributes." + key);
    if (p.texcoords[set].count != p.positions.count)
      r.fail(path + ".attributes." + key, "has a different count from POSITION");
  }
  auto tangent = prim.attributes.find("TANGENT");
  p.has_tangents = tangent != prim.attributes.end();
  if (p.has_tangents) {
    p.tangents = r.vec4(tangent->second, path + ".attributes.TANGENT");
    if (p.tangents.count != p.positions.count) r.fail(path + ".attributes.TANGENT", "has a different count from POSITION");
  }
  p.has_indices = prim.indices >= 0;
  if (p.has_indices) p.indices = r.indices(prim.indices, path + ".indices");
  size_t corners = p.has_indices ? p.indices.count : p.positions.count;
  if (corners % 3) r.fail(path + ".indices", "the count is not a multiple of 3");
  if (p.positions.count > std::numeric_limits<uint32_t>::max())
    r.fail(path + ".attributes.POSITION", "has more than 2³² vertices, which facet's indices cannot address");
  p.size.triangles = corners / 3;
  p.size.vertices = p.has_normals ? p.positions.count : corners;
  return p;
}

namespace {

// Vertex i's TANGENT in the world transform: xyz as a direction, w negated by a mirroring
// transform (`flip`: B = w·(n × t) turns with it).
std::array<double, 4> world_tangent(const Reader& r, const PrimitivePlan& p, const Mat4& world, bool flip, size_t i) {
  const std::array<double, 4> t = r.vec4_at(p.tangents, i);
  const Vec3 d = normalize(world.direction(Vec3(t[0], t[1], t[2])));
  return {d.x, d.y, d.z, (flip ? -1.0 : 1.0) * (t[3] < 0 ? -1.0 : 1.0)};
}

// Corner k of the primitive: its vertex index (in range), or k itself without indices.
uint32_t corner(const Reader& r, const PrimitivePlan& p, size_t k) {
  if (!p.has_indices) return uint32_t(k);
  uint32_t i = Reader::index_at(p.indices, k);
  if (i >= p.positions.count) r.fail(p.path + ".indices", fmt::format("index {} is out of range", i));
  return i;
}

void smooth(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh) {
  const bool flip = world.det3() < 0;
  const uint32_t base = uint32_t(mesh.positions.size());
  for (size_t i = 0; i < p.positions.count; ++i) {
    mesh.positions.push_back(world.point(r.vec3_at(p.positions, i)));
    mesh.normals.push_back(world.normal(r.vec3_at(p.normals, i)));
    for (size_t set = 0; set < 2; ++set)
      if (p.has_texcoords[set]) mesh.texcoords[set].push_back(r.vec2_at(p.texcoords[set], i));
    if (p.has_tangents) mesh.tangents.push_back(world_tangent(r, p, world, flip, i));
  }
  for (size_t t = 0; t < p.size.triangles; ++t) {
    uint32_t a = corner(r, p, 3 * t), b = corner(r, p, 3 * t + 1), c = corner(r, p, 3 * t + 2);
    if (a == b || b == c || a == c) continue;
    if (flip) std::swap(b, c);
    mesh.triangles.push_back({base + a, base + b, base + c});
  }
}

void flat(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh) {
  const bool flip = world.det3() < 0;
  for (size_t t = 0; t < p.size.triangles; ++t) {
    Vec3 a = world.point(r.vec3_at(p.positions, corner(r, p, 3 * t)));
    Vec3 b = world.point(r.vec3_at(p.positions, corner(r, p, 3 * t + 1)));
    Vec3 c = world.point(r.vec3_at(p.positions, corner(r, p, 3 * t + 2)));
    if (flip) std::swap(b, c);
    Vec3 n = cross(b - a, c - a);
    if (length(n) == 0) continue;
    n = normalize(n);
    uint32_t base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.normals.insert(mesh.normals.end(), {n, n, n});
    for (size_t set = 0; set < 2; ++set) {
      if (!p.has_texcoords[set]) continue;
      uint32_t k[3] = {corner(r, p, 3 * t), corner(r, p, 3 * t + 1), corner(r, p, 3 * t + 2)};
      if (flip) std::swap(k[1], k[2]);
      for (uint32_t v : k) mesh.texcoords[set].push_back(r.vec2_at(p.texcoords[set], v));
    }
    if (p.has_tangents) {
      uint32_t k[3] = {corner(r, p, 3 * t), corner(r, p, 3 * t + 1), corner(r, p, 3 * t + 2)};
      if (flip) std::swap(k[1], k[2]);
      for (uint32_t v : k) mesh.tangents.push_back(world_tangent(r, p, world, flip, v));
    }
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
}

}  // namespace

void append_primitive(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh,
                      std::vector<std::string>& notes) {
  const size_t first = mesh.positions.size();
  mesh.positions.reserve(first + p.size.vertices);
  mesh.normals.reserve(first + p.size.vertices);
  mesh.triangles.reserve(mesh.triangles.size() + p.size.triangles);
  // A set some primitives of the mesh have and others lack is (0, 0) on the others, said in a note.
  for (size_t set = 0; set < 2; ++set)
    if (!p.has_texcoords[set] && !mesh.texcoords[set].empty())
      notes.push_back(fmt::format("{}: no TEXCOORD_{}, which other primitives of its mesh have; (0, 0) taken", p.path, set));
  // Tangents only where every primitive of the mesh has them (a TANGENT array cannot be
  // completed by another rule without a seam): an earlier primitive without them, or this one.
  const bool lacked = first > 0 && mesh.tangents.size() != first;
  if (p.has_tangents && lacked)
    notes.push_back(p.path + ": TANGENT left, as earlier primitives of its mesh have none; MikkTSpace tangents taken");
  if (!p.has_tangents && !mesh.tangents.empty()) {
    notes.push_back(p.path + ": no TANGENT, which earlier primitives of its mesh have; MikkTSpace tangents taken");
    mesh.tangents.clear();
    mesh.tangents.shrink_to_fit();
  }
  PrimitivePlan plan = p;
  plan.has_tangents = p.has_tangents && !lacked;
  if (p.has_normals) {
    smooth(r, plan, world, mesh);
  } else {
    notes.push_back(p.path + ": no NORMAL; flat normals computed");
    flat(r, plan, world, mesh);
  }
  for (size_t set = 0; set < 2; ++set) {
    auto& tc = mesh.texcoords[set];
    if (tc.empty() || tc.size() == mesh.positions.size()) continue;
    if (p.has_texcoords[set] && tc.size() < mesh.positions.size()) {  // earlier primitives lacked it
      notes.push_back(fmt::format("{}: TEXCOORD_{}, which earlier primitives of its mesh lack; (0, 0) taken there",
                                  p.path, set));
      tc.insert(tc.begin(), mesh.positions.size() - tc.size(), {0.0, 0.0});
    } else
      tc.resize(mesh.positions.size(), {0.0, 0.0});
  }
  for (size_t i = first; i < mesh.positions.size(); ++i)
    if (!finite(mesh.positions[i]) || !finite(mesh.normals[i]))
      r.fail(p.where, "its world transform makes a vertex or a normal of " + p.path +
                          " infinite or undefined (a zero scale, or a huge one)");
}

// ---------------------------------------------------------------- the limit

std::string thousands(uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

namespace {

// MemAvailable of /proc/meminfo in bytes; 0 where it cannot be read.
uint64_t available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  uint64_t kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

std::string gigabytes(uint64_t bytes) { return fmt::format("{:.1f} GB", double(bytes) / 1e9); }

}  // namespace

void MeshBudget::add(const MeshSize& more, const std::string& file, const std::string& path, const std::string& what) {
  MeshSize t{total_.vertices + more.vertices, total_.triangles + more.triangles};
  const uint64_t bytes = t.vertices * kVertexBytes + t.triangles * kTriangleBytes;
  const std::string holds = fmt::format("{}: {} triangles and {} vertices, which would bring the scene's meshes "
                                        "to {} triangles and {} vertices",
                                        what, thousands(more.triangles), thousands(more.vertices),
                                        thousands(t.triangles), thousands(t.vertices));
  if (t.triangles > kMaxSceneTriangles || t.vertices > kMaxSceneVertices)
    throw InputError({{file, path,
                       fmt::format("{}; facet's limit is {} triangles and {} vertices in a scene (about {} in memory); "
                                   "refused before reading them",
                                   holds, thousands(kMaxSceneTriangles), thousands(kMaxSceneVertices),
                                   gigabytes(kMaxSceneTriangles * kTriangleBytes + kMaxSceneVertices * kVertexBytes)),
                       0, 0}});
  const uint64_t available = available_memory();
  if (available && bytes > available)
    throw InputError({{file, path,
                       fmt::format("{}, about {} in memory ({} bytes a vertex, {} a triangle), more than the {} "
                                   "available; refused before reading them",
                                   holds, gigabytes(bytes), kVertexBytes, kTriangleBytes, gigabytes(available)),
                       0, 0}});
  total_ = t;
}

// ---------------------------------------------------------------- files

namespace {

// tinygltf reads a glTF's external buffers through these; an import from memory
// has no folder, so it reads none (and says which it was asked for).
tinygltf::FsCallbacks no_files() {
  tinygltf::FsCallbacks fs{};
  fs.FileExists = [](const std::string&, void*) { return false; };
  fs.ExpandFilePath = [](const std::string& p, void*) { return p; };
  fs.ReadWholeFile = [](std::vector<unsigned char>*, std::string* err, const std::string& p, void*) {
    if (err) *err += "\"" + p + "\" is an external file, and an import from memory reads none\n";
    return false;
  };
  fs.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; };
  return fs;
}

// Names a missing external buffer by its key, before tinygltf reports it bare.
void check_external_buffers(const json& doc, const std::string& path, const std::string& folder) {
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array() || folder.empty()) return;
  for (size_t i = 0; i < doc["buffers"].size(); ++i) {
    const json& b = doc["buffers"][i];
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    std::string uri = b["uri"];
    if (uri.rfind("data:", 0) == 0) continue;
    fs::path file = fs::path(folder) / uri;
    if (!fs::exists(file))
      throw InputError({{path, fmt::format("buffers[{}].uri", i),
                         fmt::format("\"{}\" is not there ({}); the buffer must sit beside the glTF", uri,
                                     file.string()),
                         0, 0}});
  }
}

// An image's encoded bytes as tinygltf hands them over (a data URI's), kept as they are:
// facet decodes textures itself (core/texture.h). An image in a buffer view is read
// from its view by the import (scene/gltf_images.cpp), checked there; external files
// are not read here (TINYGLTF_NO_EXTERNAL_IMAGE).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

double number_or(const json& o, const char* key, double fallback) {
  return o.contains(key) && o[key].is_number() ? o[key].get<double>() : fallback;
}

// Each image's buffer view inside its buffer, and no data URI empty, named by key
// before tinygltf takes the image's bytes (it reads a view's bytes unchecked).
void check_image_sources(const json& doc, const std::string& path) {
  if (!doc.is_object() || !doc.contains("images") || !doc["images"].is_array()) return;
  auto fail = [&](const std::string& key, const std::string& message) {
    throw InputError({{path, key, message, 0, 0}});
  };
  const json none = json::array();
  const json& views = doc.contains("bufferViews") && doc["bufferViews"].is_array() ? doc["bufferViews"] : none;
  const json& buffers = doc.contains("buffers") && doc["buffers"].is_array() ? doc["buffers"] : none;
  for (size_t i = 0; i < doc["images"].size(); ++i) {
    const json& im = doc["images"][i];
    if (!im.is_object()) continue;
    if (im.contains("uri") && im["uri"].is_string()) {
      const std::string uri = im["uri"];
      if (uri.rfind("data:", 0) == 0 && (uri.find(',') == std::string::npos || uri.find(',') + 1 == uri.size()))
        fail(fmt::format("images[{}].uri", i), "a data URI that holds no bytes (an empty image)");
    }
    if (!im.contains("bufferView") || !im["bufferView"].is_number_integer()) continue;
    const int64_t v = im["bufferView"];
    if (v < 0 || size_t(v) >= views.size() || !views[size_t(v)].is_object())
      fail(fmt::format("images[{}].bufferView", i), fmt::format("names no buffer view ({})", v));
    const json& view = views[size_t(v)];
    const double b = number_or(view, "buffer", -1), offset = number_or(view, "byteOffset", 0),
                 length = number_or(view, "byteLength", 0);
    if (b < 0 || b >= double(buffers.size()) || !buffers[size_t(b)].is_object())
      fail(fmt::format("bufferViews[{}].buffer", v), "names no buffer");
    const double size = number_or(buffers[size_t(b)], "byteLength", 0);
    if (length <= 0) fail(fmt::format("images[{}].bufferView", i), fmt::format("bufferViews[{}] is empty (an empty image)", v));
    if (offset < 0 || offset + length > size)
      fail(fmt::format("images[{}].bufferView", i),
           fmt::format("bufferViews[{}] ({} bytes from byte {}) reaches past its buffer's {} bytes", v, length, offset, size));
  }
}

uint32_t u32(const std::string& data, size_t at) {
  uint32_t v;
  std::memcpy(&v, data.data() + at, 4);
  return v;
}

// The GLB's header and chunks (glTF 2.0 §4.4): the JSON chunk, then an optional BIN
// chunk, each inside the file; the first buffer (the BIN chunk's, having no uri) no
// longer than the chunk. Returns the JSON chunk's document.
json check_glb(const std::string& data, const std::string& path) {
  auto fail = [&](const std::string& key, const std::string& message) {
    throw InputError({{path, key, message, 0, 0}});
  };
  if (data.size() < 20 || u32(data, 0) != 0x46546C67) fail("", "is not a GLB file (no \"glTF\" header)");
  if (u32(data, 4) != 2) fail("", fmt::format("is GLB version {}; facet reads version 2", u32(data, 4)));
  if (u32(data, 8) != data.size())
    fail("", fmt::format("its header says {} bytes, the file has {}", thousands(u32(data, 8)), thousands(data.size())));
  const uint64_t json_length = u32(data, 12);
  if (u32(data, 16) != 0x4E4F534A || 20 + json_length > data.size())
    fail("", fmt::format("its first chunk is not a JSON chunk inside the file ({} bytes from byte 20 of {})",
                         thousands(json_length), thousands(data.size())));
  json doc = parse_json(data.substr(20, size_t(json_length)), path);
  uint64_t bin = 0;  // the BIN chunk's length, if there is one
  const uint64_t at = 20 + json_length;
  if (at < data.size()) {
    if (at + 8 > data.size() || u32(data, size_t(at) + 4) != 0x004E4942)
      fail("", fmt::format("the chunk after the JSON (byte {}) is not a BIN chunk", thousands(at)));
    bin = u32(data, size_t(at));
    if (at + 8 + bin > data.size())
      fail("", fmt::format("its BIN chunk claims {} bytes from byte {}; the file ends {} bytes after it",
                           thousands(bin), thousands(at + 8), thousands(data.size() - at - 8)));
  }
  if (doc.is_object() && doc.contains("buffers") && doc["buffers"].is_array() && !doc["buffers"].empty()) {
    const json& b = doc["buffers"][0];
    if (b.is_object() && !b.contains("uri") && b.contains("byteLength") && b["byteLength"].is_number() &&
        b["byteLength"].get<double>() > double(bin))
      fail("buffers[0].byteLength", fmt::format("{} bytes, more than the file's BIN chunk holds ({} bytes)",
                                                b["byteLength"].dump(), thousands(bin)));
  }
  return doc;
}

}  // namespace

tinygltf::Model load_model(const std::string& data, bool binary, const std::string& path, const std::string& folder,
                           std::vector<std::string>& notes) {
  if (data.size() > std::numeric_limits<unsigned int>::max())
    throw InputError({{path, "", "is larger than 4 GiB, which glTF cannot address", 0, 0}});
  const json doc = binary ? check_glb(data, path) : parse_json(data, path);
  check_external_buffers(doc, path, folder);
  check_image_sources(doc, path);
  tinygltf::TinyGLTF loader;
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  loader.SetImageLoader(keep_image_bytes, nullptr);
  if (folder.empty()) loader.SetFsCallbacks(no_files());
  tinygltf::Model model;
  std::string err, warn;
  auto size = static_cast<unsigned int>(data.size());
  bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                 reinterpret_cast<const unsigned char*>(data.data()), size, folder)
                   : loader.LoadASCIIFromString(&model, &err, &warn, data.data(), size, folder);
  if (!warn.empty()) notes.push_back(path + ": tinygltf: " + warn);
  if (!ok) {
    std::string msg = err.empty() ? "tinygltf could not load the file" : err;
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    throw InputError({{path, "", msg, 0, 0}});
  }
  return model;
}

tinygltf::Model load_model_file(const std::string& path, std::vector<std::string>& notes) {
  if (!fs::exists(path)) throw InputError({{path, "", "no such file", 0, 0}});
  if (!fs::is_regular_file(path)) throw InputError({{path, "", "is not a regular file", 0, 0}});
  bool binary = fs::path(path).extension() == ".glb";
  std::string folder = fs::path(path).parent_path().string();
  std::string data = read_file(path);
  return load_model(data, binary, path, folder.empty() ? "." : folder, notes);
}

}  // namespace facet::gltf_detail
