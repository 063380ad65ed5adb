// facet — the robustness sweep's grid of direction sets, defined once in the IR:
// every target prints it under its sweep harness (analysis/sweep.h runs them).
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
#pragma once

#include <vector>

#include "core/ir.h"

namespace facet {

// The 9 components n.x … v.z as functions of (s, t), in that order.
const std::vector<ir::FunctionPtr>& sweep_grid();

}  // namespace facet
