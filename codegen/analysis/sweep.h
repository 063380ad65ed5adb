// facet — numerical robustness sweeps: every model over dense sets of
// directions, hard places included, on every target: no NaN, no Inf, no
// negative value.
//
// The hard places come from one grid defined in the IR (sweep_grid()), so the
// GLSL, OSL and POV-Ray harnesses print the very generator the C++ reference
// evaluates. On an image of W × H, pixel centre (s, t) ∈ [0, 1)² lies in one
// of 8 × 8 tiles:
//   tile column a: the azimuth between l and v is a·45° (0°: l = v on the
//                  tile's diagonal; 180°: h = n on it, and l = −v where both graze);
//   tile row b:    the whole frame is turned about x by b·90°/7, ending with n
//                  parallel to the tangent axis (the tangent rule's fallback);
//   within a tile: cos θ_l and cos θ_v each run over 1 (normal incidence), 1e-7,
//                  1e-4, 0 (the horizon), −1e-7 and −0.3 (below it), then densely
//                  over [0, 1].
// Each renderer of the registry runs its own harness (Renderer::sweep); the
// direction sets and the counting are renderers/sweep.h's.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "renderers/renderer.h"
#include "renderers/sweep.h"

namespace facet {

// Every lobe model at the ends of each parameter's range (and the Fresnel and
// toon variants), as materials named "<model>_low" / "<model>_high" / ….
std::vector<Material> extreme_materials();

struct SweepOptions {
  SweepSettings settings;     // the grid, the reference's random sets; each renderer's files go to WORKDIR/<name>
  RendererSettings renderer;  // bpy's Python for Cycles
};
using SweepProgress = std::function<void(const std::string& renderer)>;  // a renderer has swept every material

// Each of `renderers` (registry names; run in the registry's order, one after
// another) sweeps every material: rows[i] holds material i's counts, one per
// renderer. A renderer that cannot run leaves its reason in its counts.
std::vector<std::vector<SweepCount>> sweep_materials(const std::vector<Material>& ms,
                                                     const std::vector<std::string>& renderers,
                                                     const SweepOptions& options, const SweepProgress& progress = {});

}  // namespace facet
