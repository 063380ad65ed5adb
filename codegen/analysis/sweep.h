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
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/ir.h"
#include "core/vec.h"
#include "renderers/renderers.h"
#include "targets/sweep_grid.h"

namespace facet {


// Every lobe model at the ends of each parameter's range (and the Fresnel and
// toon variants), as materials named "<model>_low" / "<model>_high" / ….
std::vector<Material> extreme_materials();

struct SweepCount {
  std::string target;
  size_t samples = 0;
  size_t nan = 0, inf = 0, negative = 0;  // channels, among all samples
  std::string error;                      // the target could not run
  bool ok() const { return error.empty() && samples > 0 && nan + inf + negative == 0; }
};

// The direction sets the C++ side checks: the grid (grid × grid) plus `random`
// random sets, seven eighths of them near the hard places (grazing down to
// 1e-12, l ≈ v, h ≈ n, l ≈ −v grazing, n ≈ the tangent axis, normal incidence),
// each with the tangent rule's t; `f` is evaluated on every set and counted.
using SweepFunction = std::function<RGB(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t)>;
SweepCount sweep_directions(int grid, size_t random, const Vec3& tangent_axis, const SweepFunction& f);
// The C++ reference of `m` over those sets.
SweepCount sweep_reference(const Material& m, int grid, size_t random);
// The grid's direction sets (n, l, v), row by row from pixel centre (0.5/grid, 0.5/grid).
const std::vector<std::array<Vec3, 3>>& sweep_grid_sets(int grid);
// On the targets, `source`, when not empty, replaces the generated harness (tests feed faults).
SweepCount sweep_glsl(GlRenderer& gl, const Material& m, int grid, const std::string& source = "");
// Cycles: one Blender process for the batch; the shader counts bad values itself.
std::vector<SweepCount> sweep_osl(const std::vector<Material>& ms, int grid, const std::string& python,
                                  const std::string& workdir, const std::vector<std::string>& sources = {});
// POV-Ray: the pigment shows whether each channel is finite and ≥ 0 (POV-Ray
// renders NaN black, so the test is made inside the function).
SweepCount sweep_pov(const Material& m, int grid, const std::string& workdir, const std::string& source = "");

}  // namespace facet
