// facet — the reference renderer: a C++ ray caster shading with the C++
// reference, the image every other renderer is compared with.
#pragma once

#include <cstdint>
#include <vector>

#include "catalog/material.h"
#include "core/image.h"
#include "scene/scene.h"

namespace facet {

struct Render {
  Image image;                 // linear radiance at pixel centres
  std::vector<int> object;     // per pixel: the object hit, −1 for background
  std::vector<uint8_t> grazing;  // per pixel: a shadow ray passes within 1e-4 of an occluder's edge
  // Per pixel, what makes it tell renderers apart: kFacesCamera where the surface's own normal
  // faces the eye (n·v > 0), kReceivesLight where some light reaches it (above its horizon,
  // inside its cone, not in shadow). A surface seen from behind, or reached by no light, shows
  // 0 (or its ambient and emission) on every renderer, right or wrong.
  static constexpr uint8_t kFacesCamera = 1, kReceivesLight = 2;
  std::vector<uint8_t> seen;
  // Per pixel: the surface's own unit normal (before a normal map), xyz; 0 for background.
  std::vector<float> normal;
};

// Shadow rays start this far along (relative to the scene's size) so a surface
// does not shadow itself; occluders closer than that to the point are missed.
inline constexpr double kShadowRayOffset = 1e-6;
// A shadow ray closer than this (relative) to an occluder's silhouette, or
// blocked only within this distance (relative to the scene) of its start, is
// "grazing": which side it falls on is a matter of rounding in each renderer.
inline constexpr double kGrazing = 1e-4;
// Blocks closer than this to the shaded point (scene units) are fragile too:
// POV-Ray ignores shadow hits within 1e-3 of the point (its shadow tolerance),
// Cycles and OpenGL count them.
inline constexpr double kCloseBlock = 2e-3;

// Under a normal map the light's reflectance jumps to 0 where the object's own normal
// turns from the light while the mapped one does not, and where the mapped normal turns
// from the eye: pixels within this cosine of either are fragile, as grazing shadow rays are.
inline constexpr double kNormalMapHorizon = 1e-4;

// Objects without a material of their own are shaded with `m`.
Render render_reference(const Material& m, const Scene& s, int width, int height, int threads = 0);
// Every object has its own material (Scene::has_own_materials()).
Render render_reference(const Scene& s, int width, int height, int threads = 0);

}  // namespace facet
