// facet — comparing a renderer's image with the reference, pixel by pixel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "reference/raycaster.h"

namespace facet {

// Pixels compared: the reference hit an object there and at all 8 neighbours
// (silhouettes excluded), and no shadow ray there grazes an occluder's edge.
std::vector<uint8_t> interior_mask(const Render& ref);

struct Metrics {
  double max_abs = 0;       // over interior pixels and channels
  double rmse = 0;
  double max_excess = 0;    // max |got − ref| / max(1, |ref|): compared with the tolerance
  size_t pixels = 0;        // interior pixels compared
  size_t nan = 0;           // NaN or Inf values anywhere in the image
  size_t over = 0;          // interior pixels over the tolerance
  int worst_x = -1, worst_y = -1;
  float worst_ref[3] = {0, 0, 0}, worst_got[3] = {0, 0, 0};
};

// |got − ref| ≤ tolerance · max(1, |ref|) per channel on interior pixels.
Metrics compare_images(const Render& ref, const Image& got, const std::vector<uint8_t>& mask, double tolerance);

}  // namespace facet
