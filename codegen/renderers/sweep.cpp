// The direction sets every sweep shares (renderers/sweep.h).
#include "renderers/sweep.h"

#include <cmath>
#include <map>
#include <mutex>
#include <random>

#include "reference/interpreter.h"
#include "targets/sweep_grid.h"

namespace facet {

void count_sweep_value(SweepCount& c, const RGB& r) {
  ++c.samples;
  for (double x : r) {
    if (std::isnan(x)) ++c.nan;
    else if (std::isinf(x)) ++c.inf;
    else if (x < 0) ++c.negative;
  }
}

void count_sweep_outcome(SweepCount& c, const RenderOutcome& drawn) {
  if (!drawn.ok) {
    c.error = drawn.error;
    return;
  }
  const std::vector<float>& rgb = drawn.image.rgb;
  for (size_t k = 0; k + 2 < rgb.size(); k += 3) count_sweep_value(c, {rgb[k], rgb[k + 1], rgb[k + 2]});
}

// The grid's direction sets, evaluated once per size through the IR.
const std::vector<std::array<Vec3, 3>>& sweep_grid_sets(int grid) {
  static std::map<int, std::vector<std::array<Vec3, 3>>> cache;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  auto& sets = cache[grid];
  if (!sets.empty()) return sets;
  Interpreter interp;
  std::vector<int> ids;
  for (const auto& f : sweep_grid()) ids.push_back(interp.prepare(f));
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      double s = (i + 0.5) / grid, t = (j + 0.5) / grid;
      RGB args[2] = {{s, s, s}, {t, t, t}};
      double c[9];
      for (int k = 0; k < 9; ++k) c[k] = interp.run(ids[size_t(k)], args)[0];
      sets.push_back({Vec3(c[0], c[1], c[2]), Vec3(c[3], c[4], c[5]), Vec3(c[6], c[7], c[8])});
    }
  }
  return sets;
}

SweepCount sweep_directions(int grid, size_t random, const Vec3& axis, const SweepFunction& f) {
  SweepCount c;
  c.target = "directions";
  for (const auto& set : sweep_grid_sets(grid)) count_sweep_value(c, f(set[0], set[1], set[2], tangent_rule(set[0], axis)));
  // Random sets, half of them near the hard places: grazing angles down to 1e-12,
  // l and v close to each other, to the mirror direction and to −each other, and
  // normals along the tangent axis.
  std::mt19937_64 rng(0x5eed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  auto unit = [&] { return normalize(Vec3(g(rng), g(rng), g(rng))); };
  for (size_t i = 0; i < random; ++i) {
    Vec3 n = unit(), l = unit(), v = unit();
    switch (i % 8) {
      case 0: break;  // uniform
      case 1: l = normalize(l - n * dot(n, l) + n * std::pow(10.0, -12 * u(rng))); break;  // n·l → 0⁺
      case 2: v = normalize(v - n * dot(n, v) + n * std::pow(10.0, -12 * u(rng))); break;  // n·v → 0⁺
      case 3: v = normalize(l + unit() * std::pow(10.0, -10 * u(rng))); break;              // l ≈ v
      case 4: v = normalize(n * (2 * dot(n, l)) - l + unit() * std::pow(10.0, -10 * u(rng))); break;  // h ≈ n
      case 5: {  // l ≈ −v, both grazing
        Vec3 t = normalize(cross(n, l));
        double e = std::pow(10.0, -12 * u(rng));
        l = normalize(t + n * e);
        v = normalize(-t + n * e * u(rng));
        break;
      }
      case 6: n = normalize(axis + unit() * std::pow(10.0, -10 * u(rng))); break;  // n ∥ tangent axis
      case 7: l = n; v = normalize(n + unit() * 1e-9); break;                       // normal incidence
    }
    count_sweep_value(c, f(n, l, v, tangent_rule(n, axis)));
  }
  return c;
}

}  // namespace facet
