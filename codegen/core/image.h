// facet — linear RGB float images and the files they travel in.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facet {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major from the top row, 3 floats a pixel, linear

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0.0f) {}
  float* at(int x, int y) { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
  const float* at(int x, int y) const { return &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
};

// Portable float map: exact floats (the renderers' interchange format).
void write_pfm(const std::string& path, const Image& img);
Image read_pfm(const std::string& path);
// A one-channel PFM ("Pf"), e.g. a coverage mask; rows from the top.
std::vector<float> read_pfm_grey(const std::string& path, int& width, int& height);
// A PNG's alpha channel in [0, 1] (all 1 when it has none); rows from the top.
std::vector<float> read_png_alpha(const std::string& path);
// A 16-bit (or 8-bit) PNG as linear values in [0, 1], as POV-Ray writes with File_Gamma=1.0.
Image read_png(const std::string& path);
// An 8-bit preview, values × scale clamped to [0, 1], sRGB-encoded for viewing
// (or linear, e.g. for difference images, when srgb is false).
void write_png_preview(const std::string& path, const Image& img, float scale = 1.0f, bool srgb = true);
// The bytes of an 8-bit RGB PNG (rows from the top); `path` only names it in the IoError.
std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8, const std::string& path);
// The bytes of a 16-bit PNG of `channels` 1 (grey) or 3 (RGB) values a pixel, rows from the
// top, without colour chunks (its values are data: k/65535 as stb_image reads them back).
std::string encode_png16(int width, int height, int channels, const std::vector<uint16_t>& values,
                         const std::string& path);

}  // namespace facet
