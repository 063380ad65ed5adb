// A mesh's geometry as a data image for POV-Ray's exact route (pov_mesh.h).
#include "targets/pov_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/text.h"
#include "targets/pov_printer.h"
#include "targets/templates.h"

namespace facet::targets {

namespace {

constexpr size_t kMaxBlocks = 2048;            // blocks a row at most: 4096 texels
constexpr size_t kMaxTriangles = kMaxBlocks * kMaxBlocks;
constexpr uint64_t kSplit = 32768;             // code = hi·kSplit + lo, two 16-bit channels
constexpr uint64_t kCodeLo = 2 * kSplit;       // every texel's code is in [kCodeLo, kCodeHi], so that
constexpr uint64_t kCodeHi = 65535 * kSplit;   // hi and lo stay 16-bit in the fourth texel too (split())
constexpr uint64_t kMargin = 4;                // codes left free at each end for the fourth texel's rounding

// What reading a value back adds, in codes: each channel is stored as float32(k/65535) and POV-Ray
// rounds the bilinear blend to float32 again (half an ulp each below 1: 2⁻²⁵ + 2⁻²⁵), the planar
// map adds EPSILON = 1e-10 to both coordinates (a weight of 1e-10 each), and the code itself is
// rounded (½). The lo channel weighs 1/32768 of the hi channel.
const double kReadCodes = double(65535 * (kSplit + 1)) * (std::ldexp(1.0, -24) + 2e-10) + 0.5;

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

size_t blocks_of(size_t triangles) { return std::clamp<size_t>(triangles, 1, kMaxBlocks); }

// Component c of corner k of triangle t: the position's x, y, z for c < 3, then the normal's,
// then u₀, v₀, u₁, v₁ (0 for a set the mesh lacks), then the tangent's x, y, z, w (with
// d.tangents, else 0), then the vertex colour's r, g, b, a (with d.colors), then zeros.
double corner_value(const Mesh& m, const PovMeshData& d, size_t t, int k, int c) {
  const uint32_t v = m.triangles[t][size_t(k)];
  if (c < 3) return m.positions[v][c];
  if (c < 6) return m.normals[v][c - 3];
  if (c >= 14) return d.colors && c < 18 ? m.colors[v][size_t(c - 14)] : 0;
  if (c >= 10) return d.tangents ? (*d.tangents)[3 * t + size_t(k)][size_t(c - 10)] : 0;
  const auto& set = m.texcoords[size_t(c - 6) / 2];
  return set.empty() ? 0 : set[v][size_t(c - 6) % 2];
}

// The precision POV-Ray reads component c with, in PovMeshData.
double& error_of(PovMeshData& d, size_t c) {
  if (c < 3) return d.position_error;
  if (c < 6 || (c >= 10 && c < 14)) return d.normal_error;
  return c < 10 ? d.texcoord_error : d.color_error;
}

uint64_t encode(const PovMeshData& d, int c, double v) {
  return uint64_t(std::llround((v - d.offset[size_t(c)]) / d.step[size_t(c)]));
}

// One value's four texels in a triangle's block, as (hi, lo): corners 0, 1 and 2, then
// T₁₀ + T₀₁ − T₀₀. Both channels must be linear in the block for the bilinear blend to be, so
// the fourth texel's hi and lo are hi₁ + hi₂ − hi₀ and lo₁ + lo₂ − lo₀; the corners' lo are
// their code mod 32768, or that + 32768 for corner 1 where lo₁ + lo₂ − lo₀ would be negative,
// which keeps every channel in 0 … 65535 given codes in [kCodeLo, kCodeHi].
std::array<std::array<uint16_t, 2>, 4> split(const std::array<uint64_t, 3>& code) {
  std::array<int64_t, 4> hi{}, lo{};
  for (size_t k = 0; k < 3; ++k) lo[k] = int64_t(code[k] % kSplit);
  if (lo[1] + lo[2] - lo[0] < 0) lo[1] += int64_t(kSplit);
  for (size_t k = 0; k < 3; ++k) hi[k] = (int64_t(code[k]) - lo[k]) / int64_t(kSplit);
  hi[3] = hi[1] + hi[2] - hi[0];
  lo[3] = lo[1] + lo[2] - lo[0];
  std::array<std::array<uint16_t, 2>, 4> out{};
  for (size_t k = 0; k < 4; ++k) {
    if (hi[k] < 0 || hi[k] > 65535 || lo[k] < 0 || lo[k] > 65535)
      throw std::logic_error(fmt::format("facet: a data texel out of 16 bits ({}, {})", hi[k], lo[k]));
    out[k] = {uint16_t(hi[k]), uint16_t(lo[k])};
  }
  return out;
}

}  // namespace

PovMeshData pov_mesh_data(const Mesh& m, const std::string& file, bool texcoords,
                          std::shared_ptr<const std::vector<std::array<double, 4>>> tangents, bool colors) {
  const size_t n = m.triangles.size();
  if (n > kMaxTriangles)
    throw std::invalid_argument(
        fmt::format("a mesh of {} triangles: POV-Ray's exact route holds at most {} a mesh", n, kMaxTriangles));
  PovMeshData d;
  d.file = file;
  d.blocks = int(blocks_of(n));
  d.plane_rows = int(2 * std::max<size_t>(1, (n + size_t(d.blocks) - 1) / size_t(d.blocks)));
  d.colors = colors && !m.colors.empty();
  d.components = d.colors ? 18 : tangents ? 15 : texcoords ? 12 : 6;
  d.tangents = std::move(tangents);
  const size_t components = size_t(d.components);
  // Each component's range over all four texels of every block (the fourth, T₁₀ + T₀₁ − T₀₀,
  // can lie outside the corners' range), mapped onto the codes inside the margins.
  std::array<double, 18> lo, hi;
  lo.fill(INFINITY);
  hi.fill(-INFINITY);
  for (size_t t = 0; t < n; ++t)
    for (int c = 0; c < int(components); ++c) {
      const double v0 = corner_value(m, d, t, 0, c), v1 = corner_value(m, d, t, 1, c), v2 = corner_value(m, d, t, 2, c);
      for (double v : {v0, v1, v2, v1 + v2 - v0}) {
        lo[size_t(c)] = std::min(lo[size_t(c)], v);
        hi[size_t(c)] = std::max(hi[size_t(c)], v);
      }
    }
  for (size_t c = 0; c < components; ++c) {
    if (n == 0) lo[c] = hi[c] = 0;
    const double range = std::max(hi[c] - lo[c], 1e-12 * std::max({1.0, std::abs(lo[c]), std::abs(hi[c])}));
    d.step[c] = range / double(kCodeHi - kCodeLo - 2 * kMargin);
    d.offset[c] = lo[c] - d.step[c] * double(kCodeLo + kMargin);
    double& error = error_of(d, c);
    error = std::max(error, d.step[c] * kReadCodes);
  }
  return d;
}

void write_pov_mesh_image(std::ostream& out, const Mesh& m, const PovMeshData& d) {
  const size_t n = m.triangles.size(), blocks = size_t(d.blocks), plane_rows = size_t(d.plane_rows);
  const size_t height = size_t(d.height());
  out << fmt::format("P6\n{} {}\n65535\n", d.width(), height);
  std::vector<unsigned char> row(size_t(d.width()) * 6);
  std::fill(row.begin(), row.end(), 0);
  out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));  // the row of zeros
  for (size_t file_row = 1; file_row < height; ++file_row) {  // from the top
    const size_t r = height - 1 - file_row;                     // from the bottom
    const size_t plane = r / plane_rows, j = (r % plane_rows) / 2, b = r % 2;
    const int first = 3 * int(plane / 2);  // positions, normals, texture coordinates, tangents, then colours
    const size_t part = plane % 2;        // hi, then lo
    std::fill(row.begin(), row.end(), 0);
    for (size_t i = 0; i < blocks && j * blocks + i < n; ++i) {
      const size_t t = j * blocks + i;
      for (int c = 0; c < 3; ++c) {
        std::array<uint64_t, 3> code{};
        for (int k = 0; k < 3; ++k) code[size_t(k)] = encode(d, first + c, corner_value(m, d, t, k, first + c));
        const auto texels = split(code);
        for (size_t a = 0; a < 2; ++a) {  // texel (a, b) of the block holds texels[a + 2b]
          const uint16_t v = texels[a + 2 * b][part];
          unsigned char* px = row.data() + ((2 * i + a) * 3 + size_t(c)) * 2;
          px[0] = uint8_t(v >> 8);  // big-endian
          px[1] = uint8_t(v & 255);
        }
      }
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
  }
}

std::string pov_mesh_decoder(const PovMeshData& d, size_t o) {
  // value = offset + step·code, code = 65535·(32768·hi + lo) with hi, lo the channels as read.
  std::string components;
  const char* names[] = {"PX", "PY", "PZ", "MX", "MY", "MZ", "S0", "T0", "S1", "T1", "UX", "UY",
                         "UZ", "UW", "CR", "CG", "CB", "CA"};
  for (size_t c = 0; c < std::min<size_t>(size_t(d.components), 18); ++c) {
    if ((c >= 10 && c < 14 && !d.tangents) || (c >= 14 && !d.colors)) continue;
    const size_t plane = 2 * (c / 3);
    const char channel = "RGB"[c % 3];
    components += fmt::format(
        "#declare Facet_Mesh{0}_{1} = function(U, V) {{\n  {2} + {3}*Facet_Mesh{0}_{4}(U, V, {5})\n"
        "      + {6}*Facet_Mesh{0}_{4}(U, V, {7})\n}}\n",
        o, names[c], pov_number(d.offset[c]), pov_number(d.step[c] * 65535.0 * double(kSplit)), channel, plane,
        pov_number(d.step[c] * 65535.0), plane + 1);
  }
  return render_template("pov/mesh_data.pov", {{"o", std::to_string(o)},
                                               {"file", quoted_literal(d.file)},
                                               {"blocks", std::to_string(d.blocks)},
                                               {"width", std::to_string(d.width())},
                                               {"height", std::to_string(d.height())},
                                               {"plane_rows", std::to_string(d.plane_rows)},
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

// One mesh2 declared as `name`, its vertices inset by `inset` along the normals.
void mesh2(std::ostream& out, const Mesh& m, const std::string& name, bool normals, bool numbered, double inset) {
  out << "#declare " << name << " = mesh2 {\n";
  vector_list(out, "vertex_vectors", m, false, inset);
  if (normals) vector_list(out, "normal_vectors", m, true, 0);
  const size_t n = m.triangles.size(), blocks = blocks_of(n);
  if (numbered)  // corner k of triangle t: texel (2i + [k = 1], 2j + [k = 2]) of its block (i, j)
    pov_list(out, "uv_vectors", 3 * n, 2, [&](size_t k, fmt::memory_buffer& b) {
      const size_t t = k / 3;
      fmt::format_to(std::back_inserter(b), "<{}, {}>", 2 * (t % blocks) + (k % 3 == 1), 2 * (t / blocks) + (k % 3 == 2));
    });
  pov_list(out, "face_indices", n, 2, [&](size_t i, fmt::memory_buffer& b) {
    fmt::format_to(std::back_inserter(b), "<{}, {}, {}>", m.triangles[i][0], m.triangles[i][1], m.triangles[i][2]);
  });
  if (numbered)
    pov_list(out, "uv_indices", n, 2, [&](size_t t, fmt::memory_buffer& b) {
      fmt::format_to(std::back_inserter(b), "<{}, {}, {}>", 3 * t, 3 * t + 1, 3 * t + 2);
    });
  out << "}\n";
}

}  // namespace

void write_pov_mesh_include(std::ostream& out, const Mesh& m, size_t o, const std::string& name, bool normals,
                            bool numbered, const std::vector<double>& insets) {
  out << fmt::format("// facet: mesh {} (\"{}\"), {} triangles: the mesh2 objects the scene's objects instance\n", o,
                     name, m.triangles.size());
  mesh2(out, m, fmt::format("Facet_Mesh{}", o), normals, numbered, 0);
  for (size_t k = 0; k < insets.size(); ++k)  // the copies of the one-run file, inset along the normals
    mesh2(out, m, fmt::format("Facet_Mesh{}_Copy{}", o, k + 1), normals, numbered, insets[k]);
}

}  // namespace facet::targets
