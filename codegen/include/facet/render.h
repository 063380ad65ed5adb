// facet — the reference renderer: a C++ ray caster shading with the C++
// reference, the image every other renderer is compared with.
#pragma once

#include <cstdint>
#include <vector>

#include "facet/image.h"
#include "facet/material.h"
#include "facet/scene.h"

namespace facet {

struct Render {
  Image image;                 // linear radiance at pixel centres
  std::vector<int> object;     // per pixel: the object hit, −1 for background
  std::vector<uint8_t> grazing;  // per pixel: a shadow ray passes within 1e-4 of an occluder's edge
};

// Shadow rays start this far along (relative to the scene's size) so a surface
// does not shadow itself; occluders closer than that to the point are missed.
inline constexpr double kShadowRayOffset = 1e-6;
// A shadow ray closer than this (relative) to an occluder's silhouette is
// "grazing": which side it falls on is a matter of rounding in each renderer.
inline constexpr double kGrazing = 1e-4;

Render render_reference(const Material& m, const Scene& s, int width, int height, int threads = 0);

}  // namespace facet
