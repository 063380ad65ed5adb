// A mesh's geometry as a data image for POV-Ray's exact route (pov_mesh.h).
#include "targets/pov_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include <fmt/format.h>

#include "targets/pov_printer.h"
#include "targets/templates.h"

namespace facet::targets {

namespace {

constexpr uint32_t kLevels = (1u << 24) - 1;  // 24-bit fixed point
constexpr size_t kGrid = 2048;               // triangle t ↔ uv cell (t mod 2048, t / 2048)
constexpr size_t kTexels = 9;                // per triangle
constexpr size_t kPerRow = 455;              // triangles a row of the image
constexpr int kWidth = int(kTexels * kPerRow);  // 4095 texels

// Items separated by ", ", wrapped at the scene's width, each line `indent` in.
class ListWriter {
 public:
  ListWriter(std::ostream& out, size_t indent) : out_(out), indent_(indent) {}
  void item(std::string_view s) {
    if (column_ > 0 && column_ + 2 + s.size() + 1 > kPovWidth) {
      out_ << ",\n";
      column_ = 0;
    } else if (column_ > 0) {
      out_ << ", ";
      column_ += 2;
    }
    if (column_ == 0) {
      out_ << std::string(indent_, ' ');
      column_ = indent_;
    }
    out_ << s;
    column_ += s.size();
  }
  void end() {
    if (column_ > 0) out_ << "\n";
  }

 private:
  std::ostream& out_;
  size_t indent_;
  size_t column_ = 0;
};

uint32_t quantize(double x, double lo, double step) {
  double q = std::round((x - lo) / step);
  return uint32_t(std::clamp(q, 0.0, double(kLevels)));
}

}  // namespace

PovMeshData pov_mesh_data(const Mesh& m, const std::string& file) {
  if (m.triangles.size() > kGrid * kGrid)
    throw std::invalid_argument(fmt::format("a mesh of {} triangles: POV-Ray's exact route numbers at most {}",
                                            m.triangles.size(), kGrid * kGrid));
  PovMeshData d;
  d.file = file;
  std::array<double, 3> lo = m.positions.empty() ? std::array<double, 3>{} : m.positions[0].array(), hi = lo,
                        step{};
  for (const Vec3& p : m.positions)
    for (size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[int(k)]);
      hi[k] = std::max(hi[k], p[int(k)]);
    }
  for (size_t k = 0; k < 3; ++k) step[k] = std::max(hi[k] - lo[k], 1e-30) / kLevels;
  d.lo = Vec3(lo);
  d.step = Vec3(step);
  d.normal_step = 2.0 / kLevels;
  d.width = kWidth;
  d.height = int(std::max<size_t>(1, (m.triangles.size() + kPerRow - 1) / kPerRow));
  for (const auto& t : m.triangles)
    for (uint32_t v : t)
      for (int k = 0; k < 3; ++k) {
        const Vec3 &p = m.positions[v], &n = m.normals[v];
        d.position_error =
            std::max(d.position_error, std::abs(d.lo[k] + d.step[k] * quantize(p[k], d.lo[k], d.step[k]) - p[k]));
        d.normal_error = std::max(d.normal_error, std::abs(-1 + d.normal_step * quantize(n[k], -1, d.normal_step) - n[k]));
      }
  return d;
}

void write_pov_mesh_image(std::ostream& out, const Mesh& m, const PovMeshData& d) {
  out << fmt::format("P6\n{} {}\n65535\n", d.width, d.height);
  std::vector<unsigned char> row(size_t(d.width) * 6);
  uint32_t q[18];
  for (size_t r = 0; r < size_t(d.height); ++r) {  // a row at a time: 455 triangles
    std::fill(row.begin(), row.end(), 0);
    for (size_t t = r * kPerRow; t < std::min(m.triangles.size(), (r + 1) * kPerRow); ++t) {
      for (int c = 0; c < 3; ++c) {
        const Vec3& p = m.positions[m.triangles[t][size_t(c)]];
        const Vec3& n = m.normals[m.triangles[t][size_t(c)]];
        for (int k = 0; k < 3; ++k) {
          q[3 * c + k] = quantize(p[k], d.lo[k], d.step[k]);
          q[9 + 3 * c + k] = quantize(n[k], -1, d.normal_step);
        }
      }
      // Two values a texel: R = a >> 8, G = (a & 255) << 8 | b >> 16, B = b & 65535 (big-endian).
      for (size_t j = 0; j < kTexels; ++j) {
        const uint32_t a = q[2 * j], b = q[2 * j + 1];
        const uint16_t ch[3] = {uint16_t(a >> 8), uint16_t(((a & 255u) << 8) | (b >> 16)), uint16_t(b & 65535u)};
        unsigned char* px = row.data() + ((t % kPerRow) * kTexels + j) * 6;
        for (int k = 0; k < 3; ++k) {
          px[2 * k] = uint8_t(ch[k] >> 8);
          px[2 * k + 1] = uint8_t(ch[k] & 255);
        }
      }
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
  }
}

namespace {

// Component c (x, y, z) of the position (normal = false) or the normal: value I = c (+ 9 for the
// normal) of corner 0, I + 3 of corner 1, I + 6 of corner 2; value I is in texel ⌊I/2⌋, first when I
// is even (QA), second when odd (QB).
std::string component(const PovMeshData& d, size_t o, bool normal, int c) {
  auto q = [&](int i) { return fmt::format("Facet_Mesh{}_Q{}(X, Y, {})", o, i % 2 ? "B" : "A", i / 2); };
  const int i = c + (normal ? 9 : 0);
  std::string blend = fmt::format("(1 - A - B)*{} + A*{} + B*{}", q(i), q(i + 3), q(i + 6));
  std::string value = normal ? fmt::format("{}*(\n    {}) - 1", pov_number(d.normal_step), blend)
                             : fmt::format("{} + {}*(\n    {})", pov_number(d.lo[c]), pov_number(d.step[c]), blend);
  const std::string name = fmt::format("Facet_Mesh{}_{}{}", o, normal ? "M" : "P", "XYZ"[c]);
  return fmt::format("#declare {0}at = function(X, Y, A, B) {{\n  {1}\n}}\n"
                     "#declare {0} = function(Tri, A, B) {{ {0}at(Facet_Mesh{2}_X(Tri), Facet_Mesh{2}_Y(Tri), A, B) }}\n",
                     name, value, o);
}

}  // namespace

std::string pov_mesh_decoder(const PovMeshData& d, size_t o) {
  std::string components;
  for (bool normal : {false, true})
    for (int c = 0; c < 3; ++c) components += component(d, o, normal, c);
  return render_template("pov/mesh_data.pov", {{"o", std::to_string(o)},
                                               {"file", d.file},
                                               {"height", std::to_string(d.height)},
                                               {"components", components}});
}

namespace {

// `name` { count, items } with each item from item(i, buffer).
template <typename Item>
void pov_list(std::ostream& out, const std::string& name, size_t count, size_t indent, const Item& item) {
  const std::string pad(indent, ' ');
  out << fmt::format("{0}{1} {{\n{0}  {2},\n", pad, name, count);
  ListWriter w(out, indent + 2);
  fmt::memory_buffer b;
  for (size_t i = 0; i < count; ++i) {
    b.clear();
    item(i, b);
    w.item(std::string_view(b.data(), b.size()));
  }
  w.end();
  out << pad << "}\n";
}

// float32 is what POV-Ray stores a mesh's vectors in: its shortest decimal reads back the same.
void vector_list(std::ostream& out, const std::string& name, const Mesh& m, bool normals, double inset) {
  const std::vector<Vec3>& v = normals ? m.normals : m.positions;
  pov_list(out, name, v.size(), 2, [&](size_t i, fmt::memory_buffer& b) {
    const Vec3 p = inset == 0 ? v[i] : v[i] - m.normals[i] * inset;
    fmt::format_to(std::back_inserter(b), "<{}, {}, {}>", float(p.x), float(p.y), float(p.z));
  });
}

}  // namespace

void write_pov_mesh_include(std::ostream& out, const Mesh& m, size_t o, const std::string& name, bool numbered,
                            const std::vector<double>& insets) {
  out << fmt::format("// facet: mesh {} (\"{}\"), {} triangles: the macros its mesh2 objects call\n", o, name,
                     m.triangles.size());
  out << fmt::format("#macro Facet_Mesh{}_Vertices()\n", o);
  vector_list(out, "vertex_vectors", m, false, 0);
  out << "#end\n";
  for (size_t k = 0; k < insets.size(); ++k) {  // the copies of the one-run file, inset along the normals
    out << fmt::format("#macro Facet_Mesh{}_Vertices_{}()\n", o, k + 1);
    vector_list(out, "vertex_vectors", m, false, insets[k]);
    out << "#end\n";
  }
  out << fmt::format("#macro Facet_Mesh{}_Shape()\n", o);
  vector_list(out, "normal_vectors", m, true, 0);
  const size_t n = m.triangles.size();
  if (numbered)
    pov_list(out, "uv_vectors", 3 * n, 2, [&](size_t k, fmt::memory_buffer& b) {
      const size_t t = k / 3, i = 4 * (t % kGrid) + 1 + (k % 3 == 1), j = 4 * (t / kGrid) + 1 + (k % 3 == 2);
      fmt::format_to(std::back_inserter(b), "<{}, {}>", i, j);
    });
  pov_list(out, "face_indices", n, 2, [&](size_t i, fmt::memory_buffer& b) {
    fmt::format_to(std::back_inserter(b), "<{}, {}, {}>", m.triangles[i][0], m.triangles[i][1], m.triangles[i][2]);
  });
  if (numbered)
    pov_list(out, "uv_indices", n, 2, [&](size_t t, fmt::memory_buffer& b) {
      fmt::format_to(std::back_inserter(b), "<{}, {}, {}>", 3 * t, 3 * t + 1, 3 * t + 2);
    });
  out << "#end\n";
}

}  // namespace facet::targets
