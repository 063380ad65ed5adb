#include "targets/sweep_grid.h"

#include "core/vec.h"

namespace facet {

using ir::Expr;

namespace {

// Cells per tile side along each cosine: the first six are the hard values.
const int kCells = 32;

ir::FunctionPtr sweep_cosine() {
  static const ir::FunctionPtr f = [] {
    ir::FunctionBuilder fb("sweep_cosine",
                           "facet's sweep: a cosine for x ∈ [0, 1): 1, 1e-7, 1e-4, 0, −1e-7, −0.3, then [0, 1]");
    Expr x = fb.param("x");
    Expr k = fb.let("k", ir::floor(x * double(kCells)));
    Expr dense = fb.let("dense", ir::clamp((x * double(kCells) - 6.0) / double(kCells - 7), 0.0, 1.0));
    Expr c = ir::select(k < 0.5, 1.0,
                        ir::select(k < 1.5, 1e-7,
                                   ir::select(k < 2.5, 1e-4,
                                              ir::select(k < 3.5, 0.0, ir::select(k < 4.5, -1e-7,
                                                                                  ir::select(k < 5.5, -0.3, dense))))));
    return fb.returns(c);
  }();
  return f;
}

// One component of n, l or v at (s, t): which = 3·vector + axis.
ir::FunctionPtr sweep_component(int which) {
  static const char* names[9] = {"sweep_n_x", "sweep_n_y", "sweep_n_z", "sweep_l_x", "sweep_l_y",
                                 "sweep_l_z", "sweep_v_x", "sweep_v_y", "sweep_v_z"};
  ir::FunctionBuilder fb(names[which], "facet's sweep: the hard places of the direction sets (see targets/sweep_grid.h)");
  Expr s = fb.param("s"), t = fb.param("t");
  Expr a = fb.let("a", ir::floor(s * 8.0)), b = fb.let("b", ir::floor(t * 8.0));
  Expr cl = fb.let("cl", ir::call(sweep_cosine(), {s * 8.0 - a}));
  Expr cv = fb.let("cv", ir::call(sweep_cosine(), {t * 8.0 - b}));
  Expr sl = fb.let("sl", ir::sqrt(ir::pos(1.0 - cl * cl)));
  Expr sv = fb.let("sv", ir::sqrt(ir::pos(1.0 - cv * cv)));
  Expr phi = fb.let("phi", a * (kPi / 4));
  Expr beta = fb.let("beta", b * (kPi / 14));
  Expr cb = fb.let("cb", ir::cos(beta)), sb = fb.let("sb", ir::sin(beta));
  // Local vectors (n = ẑ, l in the xz plane, v at azimuth φ), turned about x by β.
  Expr local[3][3] = {{0.0, 0.0, 1.0}, {sl, 0.0, cl}, {sv * ir::cos(phi), sv * ir::sin(phi), cv}};
  const Expr* p = local[which / 3];
  Expr out = which % 3 == 0 ? p[0] : which % 3 == 1 ? p[1] * cb - p[2] * sb : p[1] * sb + p[2] * cb;
  return fb.returns(out);
}

}  // namespace

const std::vector<ir::FunctionPtr>& sweep_grid() {
  static const std::vector<ir::FunctionPtr> grid = [] {
    std::vector<ir::FunctionPtr> g;
    for (int i = 0; i < 9; ++i) g.push_back(sweep_component(i));
    return g;
  }();
  return grid;
}

}  // namespace facet
