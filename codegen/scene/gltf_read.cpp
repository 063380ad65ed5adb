// facet's reading of glTF triangles (gltf_read.h); tinygltf's own code is compiled in gltf.cpp.
#include "scene/gltf_read.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "core/diagnostics.h"
#include "core/io.h"
#include "core/text.h"

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

// The cofactor matrix C (C_ij = (−1)^(i+j) M_ij, M_ij the minor of a_ij) is det·A⁻ᵀ: its
// rows, applied to n, give the inverse transpose up to the scale normalize() removes, and
// up to the sign of det, which a mirroring transform turns round (glTF 2.0 §3.7.2.1: the
// normal keeps facing the side the winding, reversed with it, faces). The adjugate Cᵀ
// instead would rotate a normal by the inverse rotation: the wrong way round.
Vec3 Mat4::normal(const Vec3& n) const {
  const Mat4& a = *this;
  const Vec3 row0(a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1), a(1, 2) * a(2, 0) - a(1, 0) * a(2, 2),
                  a(1, 0) * a(2, 1) - a(1, 1) * a(2, 0));
  const Vec3 row1(a(0, 2) * a(2, 1) - a(0, 1) * a(2, 2), a(0, 0) * a(2, 2) - a(0, 2) * a(2, 0),
                  a(0, 1) * a(2, 0) - a(0, 0) * a(2, 1));
  const Vec3 row2(a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1), a(0, 2) * a(1, 0) - a(0, 0) * a(1, 2),
                  a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0));
  const Vec3 r(dot(row0, n), dot(row1, n), dot(row2, n));
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

// `count` elements of `elem` bytes at `stride` from byte `offset` of buffer view `view` lie
// inside the view, and the view inside its buffer:
//   offset + stride·(count − 1) + elem ≤ view.byteLength,
//   view.byteOffset + view.byteLength ≤ buffer size,
// checked without overflowing, before any element is read.
const unsigned char* Reader::view_bytes(int view, size_t offset, size_t count, size_t elem, size_t stride,
                                        const std::string& owner) const {
  if (view < 0 || size_t(view) >= m_.bufferViews.size()) fail(owner, "has no buffer view");
  const auto& v = m_.bufferViews[size_t(view)];
  std::string vpath = fmt::format("bufferViews[{}]", view);
  if (v.buffer < 0 || size_t(v.buffer) >= m_.buffers.size()) fail(vpath + ".buffer", "names no buffer");
  const size_t size = m_.buffers[size_t(v.buffer)].data.size();
  if (v.byteOffset > size || v.byteLength > size - v.byteOffset)
    fail(vpath, fmt::format("bytes {} to {} lie past the end of buffer {} ({} bytes)", v.byteOffset,
                            uint64_t(v.byteOffset) + v.byteLength, v.buffer, size));
  if (stride < elem) fail(vpath + ".byteStride", "is smaller than one element");
  const size_t room = v.byteLength;
  bool inside = offset <= room && (count == 0 || (elem <= room - offset && (room - offset - elem) / stride >= count - 1));
  if (!inside)
    fail(owner, fmt::format("its {} elements of {} bytes (stride {}) from byte {} need more than the {} bytes of "
                            "bufferViews[{}]",
                            thousands(count), elem, stride, offset, thousands(room), view));
  return m_.buffers[size_t(v.buffer)].data.data() + v.byteOffset + offset;
}

// A sparse accessor, or one without a buffer view, as a dense copy: the base values (the
// view's, or zeros), then each of sparse.count indices (strictly increasing, each below
// count) given its value (glTF 2.0 §3.6.2.4).
AccessorView Reader::dense(int index, const tinygltf::Accessor& a, size_t elem) const {
  const std::string apath = fmt::format("accessors[{}]", index);
  if (auto made = dense_.find(index); made != dense_.end()) return {index, made->second.data(), a.count, elem, a.componentType};
  std::vector<unsigned char>& out = dense_[index];
  out.assign(a.count * elem, 0);
  if (a.bufferView >= 0) {
    if (size_t(a.bufferView) >= m_.bufferViews.size()) fail(apath, "has no buffer view");
    const size_t given = m_.bufferViews[size_t(a.bufferView)].byteStride;
    const size_t stride = given ? given : elem;
    const unsigned char* base = view_bytes(a.bufferView, a.byteOffset, a.count, elem, stride, apath);
    for (size_t i = 0; i < a.count; ++i) std::memcpy(out.data() + i * elem, base + i * stride, elem);
  }
  if (a.sparse.isSparse) {
    const auto& sp = a.sparse;
    const size_t n = size_t(std::max(sp.count, 0));
    const int itype = sp.indices.componentType;
    const int isize = tinygltf::GetComponentSizeInBytes(uint32_t(itype));
    if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(apath + ".sparse.indices.componentType", "must be an unsigned integer type");
    const AccessorView idx{index, view_bytes(sp.indices.bufferView, size_t(std::max(sp.indices.byteOffset, 0)), n,
                                             size_t(isize), size_t(isize), apath + ".sparse.indices"),
                           n, size_t(isize), itype};
    const unsigned char* values = view_bytes(sp.values.bufferView, size_t(std::max(sp.values.byteOffset, 0)), n, elem,
                                             elem, apath + ".sparse.values");
    for (size_t k = 0; k < n; ++k) {
      const uint32_t at = index_at(idx, k);
      if (at >= a.count || (k > 0 && at <= index_at(idx, k - 1)))
        fail(apath + ".sparse.indices", fmt::format("index {} ({}) is not below count {} and above the one before",
                                                    k, at, a.count));
      std::memcpy(out.data() + size_t(at) * elem, values + k * elem, elem);
    }
  }
  return {index, out.data(), a.count, elem, a.componentType};
}

// The accessor's elements, of glTF type `type`: read where they are, or made dense.
AccessorView Reader::view(int index, const std::string& path, int type) const {
  if (index < 0 || size_t(index) >= m_.accessors.size()) fail(path, fmt::format("names no accessor ({})", index));
  const auto& a = m_.accessors[size_t(index)];
  std::string apath = fmt::format("accessors[{}]", index);
  if (a.type != type)
    fail(apath, type == TINYGLTF_TYPE_VEC3   ? "expected VEC3 of FLOAT"
                : type == TINYGLTF_TYPE_VEC2 ? "expected VEC2 (texture coordinates)"
                : type == TINYGLTF_TYPE_VEC4 ? "expected VEC4"
                : type == TINYGLTF_TYPE_MAT4 ? "expected MAT4 of FLOAT"
                                             : "indices must be SCALAR");
  int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  if (component_size <= 0) fail(apath, "has an unknown componentType");
  const int width = tinygltf::GetNumComponentsInType(uint32_t(type));
  const size_t elem = size_t(component_size) * size_t(width);
  AccessorView out;
  if (a.sparse.isSparse || a.bufferView < 0) {
    out = dense(index, a, elem);
  } else {
    if (size_t(a.bufferView) >= m_.bufferViews.size()) fail(apath, "has no buffer view");
    const size_t given = m_.bufferViews[size_t(a.bufferView)].byteStride;
    out = {index, nullptr, a.count, given ? given : elem, a.componentType};
    out.data = view_bytes(a.bufferView, a.byteOffset, a.count, elem, out.stride, apath);
  }
  out.width = width;
  out.normalized = a.normalized;
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

// Component k of element i as a number: a float as it is (a non-finite one fails), a
// normalized integer as glTF 2.0 §3.11 maps it (c / max; signed: max(c / max, −1)), any
// other integer as it is.
double Reader::component_at(const AccessorView& a, size_t i, int k) const {
  const unsigned char* e = a.data + i * a.stride;
  switch (a.component) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, e + 4 * k, 4);
      if (!std::isfinite(f)) fail(fmt::format("accessors[{}]", a.accessor), fmt::format("element {} is not finite", i));
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return a.normalized ? e[k] / 255.0 : e[k];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double c = static_cast<int8_t>(e[k]);
      return a.normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, e + 2 * k, 2);
      return a.normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, e + 2 * k, 2);
      return a.normalized ? std::max(v / 32767.0, -1.0) : double(v);
    }
    default: {
      uint32_t v;
      std::memcpy(&v, e + 4 * k, 4);
      return v;
    }
  }
}

namespace {

bool float_or_normalized_unsigned(const AccessorView& a) {
  return a.component == TINYGLTF_COMPONENT_TYPE_FLOAT ||
         (a.normalized && (a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           a.component == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
}

}  // namespace

AccessorView Reader::color(int index, const std::string& path) const {
  const bool rgb = index >= 0 && size_t(index) < m_.accessors.size() && m_.accessors[size_t(index)].type == TINYGLTF_TYPE_VEC3;
  AccessorView a = view(index, path, rgb ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
  if (!float_or_normalized_unsigned(a))
    fail(fmt::format("accessors[{}]", index), "vertex colours must be FLOAT or normalized unsigned bytes or shorts");
  return a;
}

std::array<double, 4> Reader::color_at(const AccessorView& a, size_t i) const {
  std::array<double, 4> c{0, 0, 0, 1};
  for (int k = 0; k < a.width; ++k) c[size_t(k)] = component_at(a, i, k);
  return c;
}

AccessorView Reader::joints(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_VEC4);
  if (a.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.component != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
    fail(fmt::format("accessors[{}]", index), "joint indices must be unsigned bytes or shorts");
  a.normalized = false;
  return a;
}

AccessorView Reader::weights(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_VEC4);
  if (!float_or_normalized_unsigned(a))
    fail(fmt::format("accessors[{}]", index), "weights must be FLOAT or normalized unsigned bytes or shorts");
  return a;
}

AccessorView Reader::mat4(int index, const std::string& path) const {
  AccessorView a = view(index, path, TINYGLTF_TYPE_MAT4);
  if (a.component != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(fmt::format("accessors[{}]", index), "expected MAT4 of FLOAT");
  return a;
}

std::array<double, 4> Reader::quad_at(const AccessorView& a, size_t i) const {
  return {component_at(a, i, 0), component_at(a, i, 1), component_at(a, i, 2), component_at(a, i, 3)};
}

Mat4 Reader::mat4_at(const AccessorView& a, size_t i) const {
  Mat4 m;
  for (int k = 0; k < 16; ++k) m.m[k] = component_at(a, i, k);
  return m;
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

// glTF 2.0 §3.7.2.1: TRIANGLES (4, the default), TRIANGLE_STRIP (5) and TRIANGLE_FAN (6) are
// triangles; POINTS and the LINES modes have no surface to shade.
bool is_triangles(const tinygltf::Primitive& prim) {
  return prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == -1 || prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         prim.mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

PrimitivePlan plan_primitive(const Reader& r, const tinygltf::Primitive& prim, const std::string& path,
                             const std::string& where, std::array<int64_t, 2> texcoords) {
  PrimitivePlan p;
  p.prim = &prim;
  p.path = path;
  p.where = where;
  if (!is_triangles(prim))
    r.fail(path + ".mode", fmt::format("{}; facet takes triangles (modes 4, 5 and 6: triangles, strips, fans)", prim.mode));
  p.mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
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
    const std::string key = "TEXCOORD_" + std::to_string(texcoords[set]);
    auto tc = prim.attributes.find(key);
    p.has_texcoords[set] = tc != prim.attributes.end();
    if (!p.has_texcoords[set]) continue;
    p.texcoords[set] = r.vec2(tc->second, path + ".attributes." + key);
    if (p.texcoords[set].count != p.positions.count)
      r.fail(path + ".attributes." + key, "has a different count from POSITION");
  }
  auto color = prim.attributes.find("COLOR_0");
  p.has_colors = color != prim.attributes.end();
  if (p.has_colors) {
    p.colors = r.color(color->second, path + ".attributes.COLOR_0");
    if (p.colors.count != p.positions.count) r.fail(path + ".attributes.COLOR_0", "has a different count from POSITION");
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
  if (p.mode == TINYGLTF_MODE_TRIANGLES && corners % 3) r.fail(path + ".indices", "the count is not a multiple of 3");
  if (p.positions.count > std::numeric_limits<uint32_t>::max())
    r.fail(path + ".attributes.POSITION", "has more than 2³² vertices, which facet's indices cannot address");
  p.size.triangles = p.mode == TINYGLTF_MODE_TRIANGLES ? corners / 3 : corners >= 3 ? corners - 2 : 0;
  p.size.vertices = p.has_normals ? p.positions.count : 3 * p.size.triangles;  // flat: three a triangle
  return p;
}

namespace {

// Where vertex i goes: the matrix that places it (a skinned vertex's blend of its joints',
// else the node's world matrix), and its morphed attributes in the mesh's space.
class Vertices {
 public:
  Vertices(const Reader& r, const PrimitivePlan& p, const Mat4& world) : r_(r), p_(p), world_(world) {}

  Mat4 matrix(size_t i) const {
    if (!p_.skinned) return world_;
    const auto j = r_.quad_at(p_.joints, i), w = r_.quad_at(p_.weights, i);
    Mat4 m;
    for (double& e : m.m) e = 0;
    for (size_t k = 0; k < 4; ++k) {
      if (w[k] == 0) continue;
      if (j[k] >= double(p_.joint_matrices.size()))
        r_.fail(p_.path + ".attributes.JOINTS_0",
                fmt::format("vertex {} names joint {}, and the skin has {}", i, j[k], p_.joint_matrices.size()));
      const Mat4& jm = p_.joint_matrices[size_t(j[k])];
      for (int e = 0; e < 16; ++e) m.m[e] += w[k] * jm.m[e];
    }
    return m;
  }
  Vec3 position(size_t i) const {
    Vec3 v = r_.vec3_at(p_.positions, i);
    for (const auto& t : p_.morphs)
      if (t.has_positions) v = v + r_.vec3_at(t.positions, i) * t.weight;
    return v;
  }
  Vec3 normal(size_t i) const {
    Vec3 n = r_.vec3_at(p_.normals, i);
    for (const auto& t : p_.morphs)
      if (t.has_normals) n = n + r_.vec3_at(t.normals, i) * t.weight;
    return n;
  }
  // TANGENT in the world by `m`: xyz as a direction, w negated by a mirroring matrix
  // (B = w·(n × t) turns with it).
  std::array<double, 4> tangent(size_t i, const Mat4& m) const {
    const std::array<double, 4> t = r_.vec4_at(p_.tangents, i);
    Vec3 x(t[0], t[1], t[2]);
    for (const auto& g : p_.morphs)
      if (g.has_tangents) x = x + r_.vec3_at(g.tangents, i) * g.weight;
    const Vec3 d = normalize(m.direction(x));
    return {d.x, d.y, d.z, (m.det3() < 0 ? -1.0 : 1.0) * (t[3] < 0 ? -1.0 : 1.0)};
  }

 private:
  const Reader& r_;
  const PrimitivePlan& p_;
  const Mat4& world_;
};

// Corner k of the primitive's triangle list (triangle k / 3): its vertex index (in range).
// A strip's triangle t is (t, t + 1, t + 2), its odd ones (t + 1, t, t + 2) so that all keep
// the winding of the first; a fan's is (0, t + 1, t + 2) (glTF 2.0 §3.7.2.1).
uint32_t corner(const Reader& r, const PrimitivePlan& p, size_t k) {
  const size_t t = k / 3, c = k % 3;
  if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) k = t + (c == 2 ? 2 : t % 2 ? 1 - c : c);
  if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) k = c == 0 ? 0 : t + c;
  if (!p.has_indices) return uint32_t(k);
  uint32_t i = Reader::index_at(p.indices, k);
  if (i >= p.positions.count) r.fail(p.path + ".indices", fmt::format("index {} is out of range", i));
  return i;
}

void smooth(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh) {
  const Vertices vs(r, p, world);
  const uint32_t base = uint32_t(mesh.positions.size());
  std::vector<bool> mirrored(p.skinned ? p.positions.count : 0);
  for (size_t i = 0; i < p.positions.count; ++i) {
    const Mat4 m = vs.matrix(i);
    if (p.skinned) mirrored[i] = m.det3() < 0;
    mesh.positions.push_back(m.point(vs.position(i)));
    mesh.normals.push_back(m.normal(vs.normal(i)));
    for (size_t set = 0; set < 2; ++set)
      if (p.has_texcoords[set]) mesh.texcoords[set].push_back(r.vec2_at(p.texcoords[set], i));
    if (p.has_tangents) mesh.tangents.push_back(vs.tangent(i, m));
    if (p.has_colors) mesh.colors.push_back(r.color_at(p.colors, i));
  }
  const bool flip = world.det3() < 0;
  for (size_t t = 0; t < p.size.triangles; ++t) {
    uint32_t a = corner(r, p, 3 * t), b = corner(r, p, 3 * t + 1), c = corner(r, p, 3 * t + 2);
    if (a == b || b == c || a == c) continue;
    if (p.skinned ? mirrored[a] : flip) std::swap(b, c);
    mesh.triangles.push_back({base + a, base + b, base + c});
  }
}

void flat(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh) {
  const Vertices vs(r, p, world);
  for (size_t t = 0; t < p.size.triangles; ++t) {
    uint32_t k[3] = {corner(r, p, 3 * t), corner(r, p, 3 * t + 1), corner(r, p, 3 * t + 2)};
    const Mat4 m[3] = {vs.matrix(k[0]), vs.matrix(k[1]), vs.matrix(k[2])};
    Vec3 a = m[0].point(vs.position(k[0])), b = m[1].point(vs.position(k[1])), c = m[2].point(vs.position(k[2]));
    const bool flip = m[0].det3() < 0;
    if (flip) std::swap(b, c);
    Vec3 n = cross(b - a, c - a);
    if (length(n) == 0) continue;
    n = normalize(n);
    uint32_t base = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.normals.insert(mesh.normals.end(), {n, n, n});
    size_t order[3] = {0, 1, 2};
    if (flip) std::swap(order[1], order[2]);
    for (size_t set = 0; set < 2; ++set)
      if (p.has_texcoords[set])
        for (size_t o : order) mesh.texcoords[set].push_back(r.vec2_at(p.texcoords[set], k[o]));
    if (p.has_tangents)
      for (size_t o : order) mesh.tangents.push_back(vs.tangent(k[o], m[o]));
    if (p.has_colors)  // in the corners' order, turned with the winding as the positions are
      for (size_t o : order) mesh.colors.push_back(r.color_at(p.colors, k[o]));
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
}

// Morph target `t` of the primitive at `path`: its POSITION, NORMAL and TANGENT deltas
// (VEC3 of FLOAT), each with the vertex count of the base.
PrimitivePlan::Morph morph_of(const Reader& r, const PrimitivePlan& p, const std::map<std::string, int>& target,
                              double weight, const std::string& path) {
  PrimitivePlan::Morph m;
  m.weight = weight;
  auto read = [&](const char* key, AccessorView& view, bool& has) {
    auto it = target.find(key);
    if (it == target.end()) return;
    view = r.vec3(it->second, path + "." + key);
    if (view.count != p.positions.count) r.fail(path + "." + key, "has a different count from POSITION");
    has = true;
  };
  read("POSITION", m.positions, m.has_positions);
  read("NORMAL", m.normals, m.has_normals);
  read("TANGENT", m.tangents, m.has_tangents);
  return m;
}

void plan_morphs(const Reader& r, PrimitivePlan& p, const tinygltf::Mesh& mesh, int node_index,
                 std::vector<std::string>& notes) {
  if (p.prim->targets.empty()) return;
  const tinygltf::Node* node = node_index >= 0 ? &r.model().nodes[size_t(node_index)] : nullptr;
  const std::vector<double>& w = node && !node->weights.empty() ? node->weights : mesh.weights;
  const std::string wpath = node && !node->weights.empty() ? fmt::format("nodes[{}].weights", node_index) : "weights";
  if (!w.empty() && w.size() != p.prim->targets.size())
    r.fail(wpath, fmt::format("has {} weights for {} morph targets", w.size(), p.prim->targets.size()));
  for (size_t t = 0; t < p.prim->targets.size(); ++t) {
    const double weight = t < w.size() ? w[t] : 0.0;
    if (!std::isfinite(weight)) r.fail(fmt::format("{}[{}]", wpath, t), "is not finite");
    if (weight != 0)
      p.morphs.push_back(morph_of(r, p, p.prim->targets[t], weight, fmt::format("{}.targets[{}]", p.path, t)));
  }
  notes.push_back(fmt::format("{}: {} morph targets, taken at the file's weights ({} not zero; glTF's rest pose)",
                              p.path, p.prim->targets.size(), p.morphs.size()));
}

void plan_skin(const Reader& r, PrimitivePlan& p, int node_index, std::vector<std::string>& notes) {
  const tinygltf::Node& node = r.model().nodes[size_t(node_index)];
  const std::string npath = fmt::format("nodes[{}]", node_index);
  if (size_t(node.skin) >= r.model().skins.size()) r.fail(npath + ".skin", "names no skin");
  const tinygltf::Skin& skin = r.model().skins[size_t(node.skin)];
  const std::string spath = fmt::format("skins[{}]", node.skin);
  auto joints = p.prim->attributes.find("JOINTS_0"), weights = p.prim->attributes.find("WEIGHTS_0");
  if (joints == p.prim->attributes.end() || weights == p.prim->attributes.end()) {
    notes.push_back(p.path + ": its node has a skin, and it has no JOINTS_0 and WEIGHTS_0: drawn in its node's transform");
    return;
  }
  p.joints = r.joints(joints->second, p.path + ".attributes.JOINTS_0");
  p.weights = r.weights(weights->second, p.path + ".attributes.WEIGHTS_0");
  if (p.joints.count != p.positions.count || p.weights.count != p.positions.count)
    r.fail(p.path + ".attributes", "JOINTS_0 and WEIGHTS_0 need one element a vertex, as POSITION");
  AccessorView ibm;
  if (skin.inverseBindMatrices >= 0) {
    ibm = r.mat4(skin.inverseBindMatrices, spath + ".inverseBindMatrices");
    if (ibm.count < skin.joints.size()) r.fail(spath + ".inverseBindMatrices", "has fewer matrices than joints");
  }
  for (size_t k = 0; k < skin.joints.size(); ++k) {
    const int j = skin.joints[k];
    if (j < 0 || size_t(j) >= r.model().nodes.size()) r.fail(fmt::format("{}.joints[{}]", spath, k), "names no node");
    p.joint_matrices.push_back(skin.inverseBindMatrices >= 0 ? r.world_matrix(j) * r.mat4_at(ibm, k) : r.world_matrix(j));
  }
  p.skinned = true;
  notes.push_back(fmt::format("{}: skinned by {} ({} joints) at the pose of the file's node transforms; the node's "
                              "own transform is ignored, as glTF says",
                              p.path, spath, skin.joints.size()));
}

}  // namespace

void plan_deformation(const Reader& r, PrimitivePlan& p, const tinygltf::Mesh& mesh, int node_index,
                      std::vector<std::string>& notes) {
  plan_morphs(r, p, mesh, node_index, notes);
  if (node_index >= 0 && r.model().nodes[size_t(node_index)].skin >= 0) plan_skin(r, p, node_index, notes);
}

namespace {

// Vertex colours where only some primitives of a mesh have COLOR_0: the others white, which
// glTF's "no COLOR_0" means (the base colour multiplied by nothing), said in a note. `first`:
// the primitive's first vertex in the mesh.
void complete_colors(const PrimitivePlan& p, size_t first, Mesh& mesh, std::vector<std::string>& notes) {
  auto& c = mesh.colors;
  if (c.empty() || c.size() == mesh.positions.size()) return;
  constexpr std::array<double, 4> white{1, 1, 1, 1};
  if (p.has_colors) {  // earlier primitives lacked it: white before this one's
    notes.push_back(p.path + ": COLOR_0, which earlier primitives of its mesh lack; white taken there");
    c.insert(c.begin(), first, white);
  } else {
    notes.push_back(p.path + ": no COLOR_0, which other primitives of its mesh have; white taken");
    c.resize(mesh.positions.size(), white);
  }
}

// Every component of the primitive's vertex colours (from `first` in the mesh) is a number of
// [0, kColorMax], as the scene's "colors" are: a float COLOR_0 may hold anything, and a value
// out of range would not read back.
void check_colors(const Reader& r, const PrimitivePlan& p, const Mesh& mesh, size_t first) {
  if (!p.has_colors) return;
  for (size_t i = first; i < mesh.colors.size(); ++i)
    for (double x : mesh.colors[i])
      if (!(x >= 0 && x <= kColorMax))
        r.fail(fmt::format("accessors[{}]", p.colors.accessor),
               fmt::format("a vertex colour component is {}; allowed: a number in [0, {}] (COLOR_0 is a linear "
                           "colour)",
                           x, kColorMax));
}

}  // namespace

void append_primitive(const Reader& r, const PrimitivePlan& p, const Mat4& world, Mesh& mesh,
                      std::vector<std::string>& notes) {
  const size_t first = mesh.positions.size(), first_color = mesh.colors.size();
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
  check_colors(r, p, mesh, first_color);
  complete_colors(p, first, mesh, notes);
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

// The files a glTF's external buffers are, by the name tinygltf asks for them (its
// JoinPath(folder, uri)): tinygltf reads those and nothing else (no search of the working
// folder, no file outside the glTF's folder), each within read_file()'s limit.
struct BufferFiles {
  std::map<std::string, std::string> by_request;
  const std::string* lookup(const std::string& request) const {
    auto it = by_request.find(request);
    return it == by_request.end() ? nullptr : &it->second;
  }
};

tinygltf::FsCallbacks buffer_files(BufferFiles& files) {
  tinygltf::FsCallbacks cb{};
  cb.user_data = &files;
  cb.ExpandFilePath = [](const std::string& p, void*) { return p; };
  cb.FileExists = [](const std::string& p, void* u) { return static_cast<BufferFiles*>(u)->lookup(p) != nullptr; };
  cb.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& p, void* u) {
    const std::string* file = static_cast<BufferFiles*>(u)->lookup(p);
    try {
      if (!file) throw IoError(p + ": not a buffer of this glTF");
      const std::string bytes = read_file(*file);
      out->assign(bytes.begin(), bytes.end());
      return true;
    } catch (const IoError& e) {
      if (err) *err += std::string(e.what()) + "\n";
      return false;
    }
  };
  cb.WriteWholeFile = [](std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; };
  return cb;
}

// tinygltf's JoinPath: the name it asks the callbacks for.
std::string joined(const std::string& folder, const std::string& uri) {
  if (folder.empty()) return uri;
  return folder.back() == '/' || folder.back() == '\\' ? folder + uri : folder + "/" + uri;
}

// Each external buffer confined to the glTF's folder and there, named by its key, before
// tinygltf reads it.
BufferFiles external_buffers(const json& doc, const std::string& path, const std::string& folder) {
  BufferFiles files;
  if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array() || folder.empty()) return files;
  for (size_t i = 0; i < doc["buffers"].size(); ++i) {
    const json& b = doc["buffers"][i];
    if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string()) continue;
    std::string uri = b["uri"];
    if (uri.rfind("data:", 0) == 0) continue;
    const std::string key = fmt::format("buffers[{}].uri", i);
    const std::string file = uri_file(folder, uri, path, key);
    if (!fs::exists(file))
      throw InputError({{path, key, fmt::format("\"{}\" is not there ({}); the buffer must sit beside the glTF",
                                                one_line(uri), file),
                         0, 0}});
    files.by_request[joined(folder, uri)] = file;
  }
  return files;
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
  BufferFiles buffers = external_buffers(doc, path, folder);
  check_image_sources(doc, path);
  tinygltf::TinyGLTF loader;
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  loader.SetImageLoader(keep_image_bytes, nullptr);
  loader.SetFsCallbacks(folder.empty() ? no_files() : buffer_files(buffers));
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

std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

std::string uri_file(const std::string& folder, const std::string& uri, const std::string& path,
                     const std::string& key) {
  const std::string file = confined_path(folder, percent_decoded(uri));
  if (!file.empty()) return file;
  throw InputError({{path, key, outside_folder_message(uri, folder, "a glTF", "the glTF's"), 0, 0}});
}

tinygltf::Model load_model_file(const std::string& path, std::vector<std::string>& notes) {
  if (!fs::exists(path)) throw InputError({{path, "", "no such file", 0, 0}});
  // read_file refuses a folder, a device or a FIFO by name (and never blocks on one).
  bool binary = fs::path(path).extension() == ".glb";
  std::string folder = fs::path(path).parent_path().string();
  std::string data = read_file(path);
  return load_model(data, binary, path, folder.empty() ? "." : folder, notes);
}

}  // namespace facet::gltf_detail
