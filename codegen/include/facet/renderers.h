// facet — the renderers that prove the targets agree: each turns a material and
// a scene into a linear float image sampled at pixel centres.
#pragma once

#include <string>

#include "facet/image.h"
#include "facet/material.h"
#include "facet/scene.h"

namespace facet {

struct RenderJob {
  Material material;
  Scene scene;
  int width = 256, height = 256;
  std::string workdir;   // where generated code and raw outputs go (kept for inspection)
  double max_value = 1;  // the largest radiance expected (POV-Ray: sets the exposure that keeps PNGs below 1)
  // POV-Ray: bracket exposures in factors of 2 so every pixel keeps 16-bit
  // relative precision (≤ 1.5e-5 · max(1, value)); otherwise one exposure for
  // the whole image (error ≤ 7.7e-6 / exposure).
  bool bracket = false;
};

struct RenderOutcome {
  bool ok = false;
  std::string error;  // why not, when not ok: the tool's own words where it had some
  Image image;
  double seconds = 0;
  std::string log;    // what the tool printed
};

// POV-Ray 3.7: the generated scene, one frame per pass (see pov_plan) and
// exposure, each a linear 16-bit PNG with antialiasing off, rendered as one
// animation; the passes are summed and divided by their exposure.
RenderOutcome render_pov(const RenderJob& job);

}  // namespace facet
