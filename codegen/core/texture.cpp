#include "core/texture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <stb_image.h>

#include "core/io.h"

namespace facet {

namespace {

std::string stb_reason() { return stbi_failure_reason() ? stbi_failure_reason() : "unknown reason"; }

}  // namespace

std::shared_ptr<const Texels> decode_texels(const std::string& bytes, const std::string& name) {
  if (bytes.empty()) throw IoError(name + ": the image is empty (0 bytes)");
  if (bytes.size() > size_t(std::numeric_limits<int>::max())) throw IoError(name + ": the image file is over 2 GiB");
  // stb_image also reads PNM, HDR and Softimage PIC, which facet does not offer: Debian's
  // stb_image crashes on some truncated PNMs (found by the fuzzer), so they never reach it.
  const bool pnm = bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7';
  const bool hdr = bytes.compare(0, 2, "#?") == 0;
  const bool pic = bytes.compare(0, 4, "\x53\x80\xf6\x34", 4) == 0;
  if (pnm || hdr || pic)
    throw IoError(name + ": a " + (pnm ? "PNM" : hdr ? "Radiance HDR" : "Softimage PIC") +
                  " image, which facet does not read; allowed: PNG, JPEG, TGA, BMP, PSD, GIF");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int w = 0, h = 0, n = 0;
  static const char kPng[] = "\x89PNG\r\n\x1a\n";
  const bool png = bytes.compare(0, 8, kPng, 8) == 0;
  if (png && bytes.size() >= 24 && bytes.compare(12, 4, "IHDR") == 0) {
    // stb_image calls a PNG too big for it an "unknown image type": read the size from the
    // IHDR chunk (PNG §11.2.2) so that the limit below names it.
    auto be32 = [&](size_t at) {
      uint32_t v = 0;
      for (size_t i = 0; i < 4; ++i) v = v << 8 | uint8_t(bytes[at + i]);
      return v;
    };
    const double side = std::max(be32(16), be32(20));
    if (side > kMaxTextureSide)
      throw IoError(fmt::format("{}: the PNG is {}×{} texels; allowed: at most {} a side and 1 GiB decoded", name,
                                be32(16), be32(20), kMaxTextureSide));
  }
  if (!stbi_info_from_memory(data, size, &w, &h, &n))
    throw IoError(name + ": not an image facet can decode (" + stb_reason() +
                  "); allowed: PNG, JPEG, TGA, BMP, PSD, GIF");
  if (w <= 0 || h <= 0) throw IoError(fmt::format("{}: the image is {}×{} texels; it needs at least one", name, w, h));
  const double bytes_decoded = double(w) * double(h) * 4 * sizeof(float);
  if (w > kMaxTextureSide || h > kMaxTextureSide || bytes_decoded > kMaxTextureBytes)
    throw IoError(fmt::format("{}: the image is {}×{} texels ({:.2f} GiB decoded); allowed: at most {} a side and "
                              "1 GiB decoded",
                              name, w, h, bytes_decoded / kMaxTextureBytes, kMaxTextureSide));
  auto t = std::make_shared<Texels>();
  t->path = name;
  // 16 bits a channel from PNGs only: stb_image's 16-bit path for other formats (a PPM whose
  // maxval is over 255) returns a buffer of 8-bit size, which the fuzzer found read past its end.
  t->bits = png && stbi_is_16_bit_from_memory(data, size) ? 16 : 8;
  int width = 0, height = 0;
  void* px = t->bits == 16 ? static_cast<void*>(stbi_load_16_from_memory(data, size, &width, &height, &t->channels, 4))
                           : static_cast<void*>(stbi_load_from_memory(data, size, &width, &height, &t->channels, 4));
  if (!px) throw IoError(name + ": cannot decode the image (" + stb_reason() + ")");
  if (width != w || height != h) {
    stbi_image_free(px);
    throw IoError(fmt::format("{}: the image's header says {}×{} texels, its data {}×{}", name, w, h, width, height));
  }
  t->width = width;
  t->height = height;
  t->rgba.resize(size_t(width) * size_t(height) * 4);
  for (size_t i = 0; i < t->rgba.size(); ++i)
    t->rgba[i] = t->bits == 16 ? float(static_cast<const stbi_us*>(px)[i] / 65535.0)
                               : float(static_cast<const stbi_uc*>(px)[i] / 255.0);
  stbi_image_free(px);
  return t;
}

namespace {

struct TexelCache {
  std::mutex mutex;
  std::map<std::string, std::shared_ptr<const Texels>> by_path;
};

TexelCache& texel_cache() {
  static TexelCache cache;
  return cache;
}

}  // namespace

std::shared_ptr<const Texels> load_texels(const std::string& path) {
  TexelCache& cache = texel_cache();
  std::lock_guard<std::mutex> lock(cache.mutex);
  auto it = cache.by_path.find(path);
  if (it != cache.by_path.end()) return it->second;
  auto t = decode_texels(read_file(path), path);
  cache.by_path[path] = t;
  return t;
}

void remember_texels(const std::string& path, std::shared_ptr<const Texels> t) {
  TexelCache& cache = texel_cache();
  std::lock_guard<std::mutex> lock(cache.mutex);
  cache.by_path[path] = std::move(t);
}

int wrap_index(int i, int size, TextureWrap w) {
  switch (w) {
    case TextureWrap::Repeat: {
      int m = i % size;
      return m < 0 ? m + size : m;
    }
    case TextureWrap::Clamp: return i < 0 ? 0 : i >= size ? size - 1 : i;
    case TextureWrap::Mirror: {
      // glTF's MIRRORED_REPEAT (as OpenGL's): 0 1 … W−1 W−1 … 1 0 0 1 …
      int period = 2 * size;
      int m = i % period;
      if (m < 0) m += period;
      return m < size ? m : period - 1 - m;
    }
  }
  return 0;
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::array<double, 4> sample(const Texels& t, const Sampler& s, double u, double v) {
  auto texel = [&](int i, int j) {
    const float* p = t.at(wrap_index(i, t.width, s.wrap[0]), wrap_index(j, t.height, s.wrap[1]));
    std::array<double, 4> c{p[0], p[1], p[2], p[3]};
    if (s.srgb)
      for (int k = 0; k < 3; ++k) c[k] = srgb_to_linear(c[k]);
    return c;
  };
  // Far outside [0, 1] (or not a number) the index would overflow an int: no texture
  // coordinate of a real scene is there, and every target reads the same texel at ±2^24.
  auto bounded = [](double x) { return std::isfinite(x) ? std::clamp(x, -16777216.0, 16777216.0) : 0.0; };
  const double x = bounded(u * t.width), y = bounded(v * t.height);
  if (s.filter == TextureFilter::Nearest) return texel(int(std::floor(x)), int(std::floor(y)));
  // Bilinear between the four texel centres around (x − ½, y − ½).
  const double fx = x - 0.5, fy = y - 0.5;
  const int i = int(std::floor(fx)), j = int(std::floor(fy));
  const double a = fx - i, b = fy - j;
  auto c00 = texel(i, j), c10 = texel(i + 1, j), c01 = texel(i, j + 1), c11 = texel(i + 1, j + 1);
  std::array<double, 4> out{};
  for (int k = 0; k < 4; ++k)
    out[k] = (1 - b) * ((1 - a) * c00[k] + a * c10[k]) + b * ((1 - a) * c01[k] + a * c11[k]);
  return out;
}

}  // namespace facet
