#include "core/image.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <fstream>
#include <sstream>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/io.h"

// Debian's libstb exports stb_image_write's zlib compressor without declaring it.
extern "C" unsigned char* stbi_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality);

namespace facet {

void write_pfm(const std::string& path, const Image& img) {
  // PFM stores rows bottom-up, little-endian when the scale is negative.
  std::string data = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
  size_t row = size_t(img.width) * 3 * sizeof(float);
  size_t header = data.size();
  data.resize(header + row * size_t(img.height));
  for (int y = 0; y < img.height; ++y)
    std::memcpy(&data[header + row * size_t(img.height - 1 - y)], img.at(0, y), row);
  write_file_atomic(path, data);
}

Image read_pfm(const std::string& path) {
  std::string data = read_file(path);
  std::istringstream in(data);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  if (magic != "PF" || w <= 0 || h <= 0 || scale >= 0) throw IoError(path + ": not a little-endian RGB PFM image");
  in.get();  // the single whitespace after the scale
  size_t header = size_t(in.tellg());
  Image img(w, h);
  size_t row = size_t(w) * 3 * sizeof(float);
  if (data.size() < header + row * size_t(h)) throw IoError(path + ": truncated PFM image");
  for (int y = 0; y < h; ++y) std::memcpy(img.at(0, y), &data[header + row * size_t(h - 1 - y)], row);
  return img;
}

std::vector<float> read_pfm_grey(const std::string& path, int& width, int& height) {
  std::string data = read_file(path);
  std::istringstream in(data);
  std::string magic;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  if (magic != "Pf" || width <= 0 || height <= 0 || scale >= 0)
    throw IoError(path + ": not a little-endian greyscale PFM image");
  in.get();
  size_t header = size_t(in.tellg());
  size_t row = size_t(width) * sizeof(float);
  if (data.size() < header + row * size_t(height)) throw IoError(path + ": truncated PFM image");
  std::vector<float> px(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y) std::memcpy(&px[size_t(y) * size_t(width)], &data[header + row * size_t(height - 1 - y)], row);
  return px;
}

std::vector<float> read_png_alpha(const std::string& path) {
  int w = 0, h = 0, n = 0;
  stbi_us* px = stbi_load_16(path.c_str(), &w, &h, &n, 4);
  if (!px) throw IoError(path + ": cannot read the PNG: " + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
  std::vector<float> alpha(size_t(w) * size_t(h));
  for (size_t i = 0; i < alpha.size(); ++i) alpha[i] = float(px[i * 4 + 3] / 65535.0);
  stbi_image_free(px);
  return alpha;
}

Image read_png(const std::string& path) {
  int w = 0, h = 0, n = 0;
  stbi_us* px = stbi_load_16(path.c_str(), &w, &h, &n, 3);
  if (!px) throw IoError(path + ": cannot read the PNG: " + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
  Image img(w, h);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = float(px[i] / 65535.0);
  stbi_image_free(px);
  return img;
}

void write_png_preview(const std::string& path, const Image& img, float scale, bool srgb) {
  std::vector<uint8_t> px(img.rgb.size());
  for (size_t i = 0; i < px.size(); ++i) {
    float v = img.rgb[i] * scale;
    if (!(v > 0)) v = 0;  // NaN shows black
    if (v > 1) v = 1;
    float s = !srgb ? v : v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
    px[i] = uint8_t(std::lround(s * 255));
  }
  write_file_atomic(path, encode_png(img.width, img.height, px, path));
}

std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8, const std::string& path) {
  std::string data;
  auto append = [](void* context, void* bytes, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(bytes), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &data, width, height, 3, rgb8.data(), width * 3))
    throw IoError(path + ": cannot encode the PNG");
  return data;
}

namespace {

uint32_t png_crc(const std::string& bytes) {
  static uint32_t table[256] = {};
  if (!table[1])
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[n] = c;
    }
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void put_u32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(char((v >> s) & 0xFF));
}

// A PNG chunk (PNG specification §5.3): length, type, data, CRC of type and data.
void png_chunk(std::string& out, const char* type, const std::string& data) {
  put_u32(out, uint32_t(data.size()));
  std::string body = std::string(type, 4) + data;
  out += body;
  put_u32(out, png_crc(body));
}

}  // namespace

std::string encode_png16(int width, int height, int channels, const std::vector<uint16_t>& values,
                         const std::string& path) {
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3) ||
      values.size() != size_t(width) * size_t(height) * size_t(channels))
    throw IoError(path + ": cannot encode the PNG (its size and its values disagree)");
  const size_t row = size_t(width) * size_t(channels) * 2 + 1;
  if (row * size_t(height) > size_t(std::numeric_limits<int>::max()))
    throw IoError(path + ": cannot encode the PNG (over 2 GiB)");
  std::vector<unsigned char> raw(row * size_t(height));
  for (size_t j = 0; j < size_t(height); ++j) {
    unsigned char* r = &raw[j * row];
    r[0] = 0;  // filter: none
    for (size_t i = 0; i < row / 2; ++i) {
      const uint16_t v = values[j * (row / 2) + i];
      r[1 + 2 * i] = uint8_t(v >> 8);  // big-endian samples
      r[2 + 2 * i] = uint8_t(v & 0xFF);
    }
  }
  int zlen = 0;
  unsigned char* z = stbi_zlib_compress(raw.data(), int(raw.size()), &zlen, 8);
  if (!z) throw IoError(path + ": cannot encode the PNG (compression failed)");
  std::string idat(reinterpret_cast<const char*>(z), size_t(zlen));
  std::free(z);
  std::string out("\x89PNG\r\n\x1a\n", 8), ihdr;
  put_u32(ihdr, uint32_t(width));
  put_u32(ihdr, uint32_t(height));
  ihdr += std::string{char(16), char(channels == 3 ? 2 : 0), 0, 0, 0};  // depth, colour type, compression, filter, interlace
  png_chunk(out, "IHDR", ihdr);
  png_chunk(out, "IDAT", idat);
  png_chunk(out, "IEND", "");
  return out;
}

}  // namespace facet
