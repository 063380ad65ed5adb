#include "renderers/compare.h"

#include <algorithm>
#include <cmath>

namespace facet {

std::vector<uint8_t> interior_mask(const Render& ref) {
  const int w = ref.image.width, h = ref.image.height;
  std::vector<uint8_t> mask(size_t(w) * size_t(h), 0);
  for (int y = 1; y + 1 < h; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      size_t i = size_t(y) * size_t(w) + size_t(x);
      int o = ref.object[i];
      if (o < 0 || ref.grazing[i]) continue;
      bool same = true;
      for (int dy = -1; dy <= 1 && same; ++dy)
        for (int dx = -1; dx <= 1 && same; ++dx)
          same = ref.object[size_t(y + dy) * size_t(w) + size_t(x + dx)] == o;
      mask[i] = same;
    }
  }
  return mask;
}

Metrics compare_images(const Render& ref, const Image& got, const std::vector<uint8_t>& mask, double tolerance) {
  Metrics m;
  double sum2 = 0;
  size_t count = 0;
  for (float v : got.rgb)
    if (!std::isfinite(v)) ++m.nan;
  for (int y = 0; y < got.height; ++y) {
    for (int x = 0; x < got.width; ++x) {
      size_t i = size_t(y) * size_t(got.width) + size_t(x);
      if (!mask[i]) continue;
      const float* a = ref.image.at(x, y);
      const float* b = got.at(x, y);
      ++m.pixels;
      bool over = false;
      for (int c = 0; c < 3; ++c) {
        double d = std::fabs(double(b[c]) - double(a[c]));
        if (!std::isfinite(d)) d = INFINITY;
        double excess = d / std::max(1.0, std::fabs(double(a[c])));
        if (d > m.max_abs || (m.worst_x < 0)) {
          if (d > m.max_abs || m.worst_x < 0) {
            m.worst_x = x;
            m.worst_y = y;
            std::copy(a, a + 3, m.worst_ref);
            std::copy(b, b + 3, m.worst_got);
          }
          m.max_abs = std::max(m.max_abs, d);
        }
        m.max_excess = std::max(m.max_excess, excess);
        if (excess > tolerance) over = true;
        sum2 += d * d;
        ++count;
      }
      if (over) ++m.over;
    }
  }
  m.rmse = count ? std::sqrt(sum2 / double(count)) : 0;
  return m;
}

}  // namespace facet
