// facet — what every renderer's robustness sweep shares (analysis/sweep.h explains
// the sweep): the grid's direction sets the harnesses generate, the C++ side's
// own sets, and the counting of bad values.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/ir.h"
#include "core/vec.h"
#include "renderers/renderer.h"

namespace facet {

// One sample's channels into `c`: NaN, Inf and negative values each in their column.
void count_sweep_value(SweepCount& c, const RGB& value);
// Every pixel of a harness's image into `c`, or its error where it drew nothing.
void count_sweep_outcome(SweepCount& c, const RenderOutcome& drawn);

// The grid's direction sets (n, l, v), row by row from pixel centre (0.5/grid, 0.5/grid).
const std::vector<std::array<Vec3, 3>>& sweep_grid_sets(int grid);

// The direction sets the C++ side checks: the grid (grid × grid) plus `random`
// random sets, seven eighths of them near the hard places (grazing down to
// 1e-12, l ≈ v, h ≈ n, l ≈ −v grazing, n ≈ the tangent axis, normal incidence),
// each with the tangent rule's t; `f` is evaluated on every set and counted.
using SweepFunction = std::function<RGB(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t)>;
SweepCount sweep_directions(int grid, size_t random, const Vec3& tangent_axis, const SweepFunction& f);

}  // namespace facet
