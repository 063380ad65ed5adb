// libFuzzer target: image decoding (core/texture.h). Every byte string either
// decodes into texels that every filter and wrap samples to finite values in
// [0, 1], or is refused with an IoError naming the image.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/io.h"
#include "core/texture.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  std::shared_ptr<const facet::Texels> t;
  try {
    t = facet::decode_texels(bytes, "fuzz.png");
  } catch (const facet::IoError&) {
    return 0;
  }
  const double at[][2] = {{0, 0}, {0.5, 0.5}, {0.999, 0.001}, {-1.25, 2.5}, {1e7, -1e7}};
  for (auto filter : {facet::TextureFilter::Nearest, facet::TextureFilter::Bilinear})
    for (auto wrap : {facet::TextureWrap::Repeat, facet::TextureWrap::Clamp, facet::TextureWrap::Mirror})
      for (bool srgb : {false, true})
        for (const auto& uv : at) {
          facet::Sampler s;
          s.filter = filter;
          s.wrap = {wrap, wrap};
          s.srgb = srgb;
          for (double c : facet::sample(*t, s, uv[0], uv[1]))
            if (!(c >= -1e-12 && c <= 1 + 1e-12)) {
              std::fprintf(stderr, "fuzz: texture: a sample %g outside [0, 1]\n", c);
              std::abort();
            }
        }
  return 0;
}
