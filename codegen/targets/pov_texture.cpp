#include "targets/pov_texture.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/text.h"
#include "targets/pov_printer.h"

namespace facet::targets {

using ir::Expr;

namespace {

const char* kChannels[] = {"R", "G", "B", "A"};

// The wrap of a whole texel index I into [0, N) as SDL: 0 repeat, 1 clamp, 2 mirror.
std::string wrap_sdl(const char* index, int size, int mode) {
  if (mode == 1) return fmt::format("min(max({}, 0), {})", index, size - 1);
  if (mode == 0) return fmt::format("({0} - {1}*floor({0}/{1}))", index, size);
  return fmt::format("Facet_Mirror({}, {})", index, size);
}

// A texel-reading function: the stub the IR calls, printed _R, _G, _B (channel-dependent:
// its result holds a colour that is not grey), or one channel's.
ir::FunctionPtr texel_stub(int image, int channel) {
  auto f = std::const_pointer_cast<ir::Function>(declared(
      channel < 0 ? fmt::format("Facet_Texel{}", image) : fmt::format("Facet_Texel{}_{}", image, kChannels[channel]), 2));
  if (channel < 0) f->result = ir::color(1, 2, 3);  // never printed: makes the calls per channel
  return f;
}

// Facet_Rgb(R, G, B): printed as Facet_Rgb_R, _G, _B (its result a colour that is not grey).
ir::FunctionPtr rgb_stub() {
  static const ir::FunctionPtr f = [] {
    auto g = std::const_pointer_cast<ir::Function>(declared("Facet_Rgb", 3));
    g->result = ir::color(1, 2, 3);  // never printed: makes the calls per channel
    return ir::FunctionPtr(g);
  }();
  return f;
}

}  // namespace

std::string pov_texture_declarations(const PovTexture& t) {
  const TextureCall& c = t.call;
  const int w = c.texels->width, h = c.texels->height;
  std::string out = fmt::format("// Image {} (\"{}\", {}×{}): its texels as facet decoded them, in {}.\n", t.image,
                                c.file, w, h, t.file);
  out += fmt::format("#declare Facet_Image{} = function {{ pigment {{ image_map {{ ppm {} gamma 1.0 }} }} }}\n",
                     t.image, quoted_literal(t.file));
  if (!t.alpha.empty())
    out += fmt::format("#declare Facet_Alpha{} = function {{ pigment {{ image_map {{ pgm {} gamma 1.0 }} }} }}\n",
                       t.image, quoted_literal(t.alpha));
  const std::string i = wrap_sdl("I", w, c.wrap[0]), j = wrap_sdl("J", h, c.wrap[1]);
  // Row J of the file is row J + 1 of the image (the row of zeros on top), from the top.
  const std::string at = fmt::format("({} + 0.5)/{}, 1 - ({} + 1.5)/{}, 0", i, w, j, h + 1);
  for (int ch = 0; ch < 4; ++ch) {
    if (ch == 3 && t.alpha.empty()) continue;
    std::string raw = ch == 3 ? fmt::format("Facet_Alpha{}({}).gray", t.image, at)
                              : fmt::format("Facet_Image{}({}).{}", t.image, at, ch == 0 ? "red" : ch == 1 ? "green" : "blue");
    if (c.srgb && ch < 3) raw = "Facet_Srgb(" + raw + ")";
    out += fmt::format("#declare Facet_Texel{}_{} = function(I, J) {{ {} }}\n", t.image, kChannels[ch], raw);
  }
  return out;
}

void write_pov_texture_image(std::ostream& out, const Texels& t, bool alpha) {
  const int channels = alpha ? 1 : 3;
  out << fmt::format("{}\n{} {}\n65535\n", alpha ? "P5" : "P6", t.width, t.height + 1);
  std::vector<unsigned char> row(size_t(t.width) * size_t(channels) * 2, 0);
  out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));  // the row of zeros
  for (int j = 0; j < t.height; ++j) {
    for (int i = 0; i < t.width; ++i)
      for (int k = 0; k < channels; ++k) {
        const unsigned v = unsigned(std::lround(double(t.at(i, j)[alpha ? 3 : k]) * 65535.0));
        row[size_t(i * channels + k) * 2] = static_cast<unsigned char>(v >> 8);
        row[size_t(i * channels + k) * 2 + 1] = static_cast<unsigned char>(v & 255);
      }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
  }
}

namespace {

// channel(texture(S′, T′)) of call t: nearest or bilinear, S and T transformed.
Expr sampled(ir::FunctionBuilder& fb, const PovTexture& t, Expr s, Expr tt) {
  const TextureCall& c = t.call;
  if (c.transformed) {
    Expr s2 = fb.let("Su", c.a * s + c.b * tt + c.ou);
    tt = fb.let("Tv", c.c * s + c.d * tt + c.ov);
    s = s2;
  }
  const ir::FunctionPtr texel = texel_stub(t.image, c.channel);
  const double w = c.texels->width, h = c.texels->height;
  auto read = [&](const Expr& i, const Expr& j) { return ir::call(texel, {i, j}); };
  if (!c.bilinear) return read(ir::floor(s * w), ir::floor(tt * h));
  Expr x = fb.let("X", s * w - 0.5), y = fb.let("Y", tt * h - 0.5);
  Expr i = fb.let("I", ir::floor(x)), j = fb.let("J", ir::floor(y));
  Expr a = fb.let("A", x - i), b = fb.let("B", y - j);
  return (1.0 - b) * ((1.0 - a) * read(i, j) + a * read(i + 1.0, j)) +
         b * ((1.0 - a) * read(i, j + 1.0) + a * read(i + 1.0, j + 1.0));
}

// A colour (three lanes unless grey) or a number.
Expr lanes(const TextureCall& c, const std::array<double, 3>& x) {
  return c.color && !(x[0] == x[1] && x[1] == x[2]) ? ir::color(x[0], x[1], x[2]) : Expr(x[0]);
}

}  // namespace

ir::FunctionPtr pov_sample_function(const PovTexture& t) {
  const TextureCall& c = t.call;
  ir::FunctionBuilder fb("Facet_Sample_" + c.name, "");
  std::optional<Expr> s, tt;
  if (c.image) s = fb.param("S"), tt = fb.param("T");
  // offset + factor ⊗ texel ⊗ vc, as every target computes it (texture_value_code()).
  Expr value = lanes(c, c.factor);
  if (c.image) value = value * sampled(fb, t, *s, *tt);
  if (c.vertex_color) {
    const Expr r = fb.param("R"), g = fb.param("G"), b = fb.param("B"), a = fb.param("A");
    const Expr component[] = {r, g, b, a};
    value = value * (c.color ? ir::call(rgb_stub(), {r, g, b}) : component[std::max(c.channel, 0)]);
  }
  if (!c.offset_zero()) value = lanes(c, c.offset) + value;
  value = std::isfinite(c.hi) ? ir::clamp(value, c.lo, c.hi) : ir::max(value, c.lo);
  return fb.returns(value);
}

PovTexture pov_lane(const PovTexture& t, int k, const std::string& name) {
  PovTexture lane = t;
  const size_t i = size_t(k);
  lane.call.name = name + "_" + "rgb"[i];
  lane.call.color = false;
  lane.call.channel = k;
  lane.call.factor = {t.call.factor[i], t.call.factor[i], t.call.factor[i]};
  lane.call.offset = {t.call.offset[i], t.call.offset[i], t.call.offset[i]};
  return lane;
}

std::vector<ir::FunctionPtr> pov_max_sample_functions(const PovTexture& t, const std::string& name) {
  const TextureCall& c = t.call;
  ir::FunctionBuilder fb("Facet_Sample_" + name, "");
  std::vector<Expr> args;
  if (c.image) args = {fb.param("S"), fb.param("T")};
  if (c.vertex_color)
    for (const char* v : {"R", "G", "B", "A"}) args.push_back(fb.param(v));
  std::vector<ir::FunctionPtr> out;
  std::optional<Expr> largest;
  for (int k = 0; k < 3; ++k) {
    out.push_back(pov_sample_function(pov_lane(t, k, name)));
    Expr value = ir::call(out.back(), args);
    largest = largest ? ir::max(*largest, value) : value;
  }
  out.push_back(fb.returns(*largest));
  return out;
}

std::string pov_rgb_declarations() {
  std::string out = "// A colour from three numbers, channel by channel: a vertex colour's rgb.\n";
  for (int ch = 0; ch < 3; ++ch)
    out += fmt::format("#declare Facet_Rgb_{} = function(R, G, B) {{ {} }}\n", kChannels[ch], "RGB"[ch]);
  return out;
}

}  // namespace facet::targets
