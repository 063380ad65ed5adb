// facet — image textures: the decoded texels and the one sampling rule every
// target follows (docs/textures.md).
//
// The convention is glTF's: (u, v) = (0, 0) is the top-left corner of the
// picture, v grows down the rows, texel (i, j) covers [i, i+1)/W × [j, j+1)/H
// and its centre is ((i + ½)/W, (j + ½)/H). Wrapping acts on whole texel
// indices; sRGB is decoded per texel, before the bilinear blend.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace facet {

// A decoded image: raw channel values k/255 (8-bit files) or k/65535 (16-bit),
// as floats, four a texel (grey is replicated to r, g, b; alpha is 1 where the
// file has none), row 0 the top of the picture.
struct Texels {
  std::string path;
  int width = 0, height = 0;
  int channels = 0;  // in the file: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  int bits = 8;      // per channel in the file: 8 or 16
  std::vector<float> rgba;
  const float* at(int i, int j) const { return &rgba[(size_t(j) * size_t(width) + size_t(i)) * 4]; }
};

// The largest image facet decodes: 16384 texels a side and 1 GiB of decoded texels.
inline constexpr int kMaxTextureSide = 16384;
inline constexpr double kMaxTextureBytes = 1024.0 * 1024.0 * 1024.0;

// Decodes a PNG, JPEG, TGA, BMP, PSD, GIF, HDR-less file with stb_image (each file
// once per process: a cache keyed by its path). Throws IoError naming the file and
// the reason (missing, unreadable, not an image, zero-sized, too big).
std::shared_ptr<const Texels> load_texels(const std::string& path);
// The same from bytes in memory (a GLB's embedded image, a data URI); `name` names it in errors.
std::shared_ptr<const Texels> decode_texels(const std::string& bytes, const std::string& name);
// Puts `t` in load_texels's cache under `path`: an image decoded from memory (a glTF's
// embedded image, an image baked by the import) that is to be written at `path` reads
// as that file before it is written.
void remember_texels(const std::string& path, std::shared_ptr<const Texels> t);

enum class TextureFilter { Nearest, Bilinear };
enum class TextureWrap { Repeat, Clamp, Mirror };

struct Sampler {
  TextureFilter filter = TextureFilter::Bilinear;
  std::array<TextureWrap, 2> wrap{TextureWrap::Repeat, TextureWrap::Repeat};  // u, then v
  bool srgb = false;  // decode r, g, b from sRGB (IEC 61966-2-1) per texel; alpha stays linear
};

// A texel index wrapped into [0, size).
int wrap_index(int i, int size, TextureWrap w);
// IEC 61966-2-1: c ≤ 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4.
double srgb_to_linear(double c);
// The filtered RGBA at (u, v) in double precision: what every target must compute.
std::array<double, 4> sample(const Texels& t, const Sampler& s, double u, double v);

}  // namespace facet
