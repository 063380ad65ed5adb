// KHR_materials_sheen's terms (README, "Implementation Notes"): the "Charlie" distribution and
// visibility of Conty & Kulla 2017, and E, the directional albedo the base is scaled by.
// E is a fit (scripts/fit_sheen_albedo.py; its table sheen_albedo_table.inc holds log(E + ε) at
// Gauss–Chebyshev nodes for rows of sheen roughness): a material's roughness is interpolated
// between rows and the series' coefficients computed when its code is generated, so a target
// evaluates three Chebyshev series in μ^¼ or √μ, one per piece of μ, the same on every target.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "catalog/catalog.h"
#include "core/vec.h"

namespace facet {

namespace {
#include "catalog/sheen_albedo_table.inc"

constexpr int kMuPieces = static_cast<int>(std::size(kSheenAlbedoMuPieces)) - 1;

// T_0(x) … T_n(x).
std::vector<double> chebyshev(double x, int n) {
  std::vector<double> t(static_cast<size_t>(n) + 1);
  t[0] = 1;
  if (n > 0) t[1] = x;
  for (int k = 2; k <= n; ++k) t[k] = 2 * x * t[k - 1] - t[k - 2];
  return t;
}

// log(E + ε) at the nodes of μ piece `piece` for sheen roughness r: cubic Lagrange over the four
// nearest rows (the script's interpolate_row).
std::array<double, kSheenAlbedoNodes> row_at(double r, int piece) {
  const int rows = static_cast<int>(std::size(kSheenAlbedoRows));
  r = std::clamp(r, kSheenAlbedoRows[0], 1.0);
  const int above = static_cast<int>(std::lower_bound(kSheenAlbedoRows, kSheenAlbedoRows + rows, r) - kSheenAlbedoRows);
  const int i = std::clamp(above - 2, 0, rows - 4);
  std::array<double, kSheenAlbedoNodes> y{};
  for (int a = 0; a < 4; ++a) {
    double w = 1;
    for (int b = 0; b < 4; ++b)
      if (b != a) w *= (r - kSheenAlbedoRows[i + b]) / (kSheenAlbedoRows[i + a] - kSheenAlbedoRows[i + b]);
    for (int j = 0; j < kSheenAlbedoNodes; ++j) y[j] += w * kSheenAlbedoTable[i + a][piece][j];
  }
  return y;
}

}  // namespace

double sheen_albedo_worst_error() { return kSheenAlbedoWorstError; }

std::vector<SheenAlbedoPiece> sheen_albedo_pieces(double sheen_roughness) {
  std::vector<SheenAlbedoPiece> out;
  const double n = kSheenAlbedoNodes;
  for (int p = 0; p < kMuPieces; ++p) {
    SheenAlbedoPiece piece;
    piece.mu_end = kSheenAlbedoMuPieces[p + 1];
    piece.power = kSheenAlbedoPowers[p];
    // The lobe takes m^q as √m or √√m (catalog/specular.cpp, gltf_sheen).
    if (piece.power != 0.5 && piece.power != 0.25) throw std::logic_error("sheen albedo: a piece's power is not ½ or ¼");
    const double lo = std::pow(kSheenAlbedoMuPieces[p], piece.power), hi = std::pow(piece.mu_end, piece.power);
    piece.scale = 2 / (hi - lo);
    piece.offset = -2 * lo / (hi - lo) - 1;
    const auto y = row_at(sheen_roughness, p);
    // The interpolant through the Gauss nodes: a_k = (2/N) Σ_j y_j cos(π k (j + ½) / N), a_0 halved.
    for (int k = 0; k < kSheenAlbedoNodes; ++k) {
      double a = 0;
      for (int j = 0; j < kSheenAlbedoNodes; ++j) a += y[j] * std::cos(kPi * k * (j + 0.5) / n);
      piece.coefficients.push_back((k == 0 ? 1 : 2) * a / n);
    }
    out.push_back(piece);
  }
  return out;
}

double sheen_albedo_epsilon() { return kSheenAlbedoEpsilon; }
double sheen_albedo_mu_min() { return kSheenAlbedoMuPieces[0]; }

double sheen_albedo(double mu, double sheen_roughness) {
  const auto pieces = sheen_albedo_pieces(sheen_roughness);
  const double m = std::max(mu, kSheenAlbedoMuPieces[0]);
  int p = 0;
  while (p + 1 < kMuPieces && m >= pieces[p].mu_end) ++p;
  const double x = pieces[p].scale * std::pow(m, pieces[p].power) + pieces[p].offset;  // as the lobe maps it
  const std::vector<double> t = chebyshev(x, kSheenAlbedoNodes - 1);
  double s = 0;
  for (int k = 0; k < kSheenAlbedoNodes; ++k) s += pieces[p].coefficients[k] * t[k];
  return std::clamp(std::exp(s) - kSheenAlbedoEpsilon, 0.0, 1.0);
}

std::array<double, 6> sheen_visibility_constants(double alpha) {
  // The README's l(x, alpha_g): each of a … e is mix(p, q, (1 − α)²).
  const double t = (1 - alpha) * (1 - alpha);
  auto mix = [t](double p, double q) { return p + (q - p) * t; };
  const double a = mix(21.5473, 25.3245), b = mix(3.82987, 3.32435), c = mix(0.19823, 0.16801),
               d = mix(-1.97760, -1.27393), e = mix(-4.32054, -4.85967);
  return {a, b, c, d, e, a / (1 + b * std::pow(0.5, c)) + d * 0.5 + e};
}

namespace terms {

using ir::Expr;
using ir::FunctionBuilder;
using ir::FunctionPtr;

FunctionPtr distribution_charlie() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("D_charlie",
                       "KHR_materials_sheen, \"Sheen distribution\" (Conty & Kulla 2017, \"Charlie\"): "
                       "D = (2 + 1/α) (sin²θ_h)^(1/(2α)) / (2π), α = sheenRoughness²",
                       "sin²θ_h = (1 − n·h)(1 + n·h), clamped into [0, 1] as a power's base.");
    Expr NoH = fb.param("NoH"), alpha = fb.param("alpha");
    Expr inv_r = fb.let("inv_r", 1.0 / alpha);
    Expr sin2h = fb.let("sin2h", ir::unit((1.0 - NoH) * (1.0 + NoH)));
    return fb.returns((2.0 + inv_r) * ir::pow(sin2h, inv_r * 0.5) / (2.0 * kPi));
  }();
  return f;
}

// lambda_sheen(cos θ) = exp(l(|cos θ|)) below 0.5, else exp(2 l(0.5) − l(1 − |cos θ|)), with the
// README's l(x) = a / (1 + b x^c) + d x + e: one l() of the argument chosen first; a … e and
// l(0.5) depend on α alone and come in as the material's constants (sheen_visibility_constants).
FunctionPtr sheen_lambda() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("sheen_lambda",
                       "KHR_materials_sheen, \"Sheen visibility\": lambda_sheen = exp(l(|cos θ|)) where "
                       "|cos θ| < 0.5, else exp(2 l(0.5) − l(1 − |cos θ|)), l(x) = a / (1 + b x^c) + d x + e",
                       "a … e are mixed by (1 − α)² and l(0.5) computed when the code is generated; x is a cosine, "
                       "clamped into [0, 1] as a power's base.");
    Expr cos_theta = fb.param("cos_theta");
    Expr a = fb.param("a"), b = fb.param("b"), c = fb.param("c"), d = fb.param("d"), e = fb.param("e");
    Expr l_half = fb.param("l_half");
    Expr x = fb.let("x", ir::abs(cos_theta));
    Expr y = fb.let("y", ir::select(x < 0.5, x, 1.0 - x));
    Expr l = fb.let("l", a / (1.0 + b * ir::pow(ir::unit(y), c)) + d * y + e);
    return fb.returns(ir::exp(ir::select(x < 0.5, l, 2.0 * l_half - l)));
  }();
  return f;
}

FunctionPtr visibility_charlie() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("V_charlie",
                       "KHR_materials_sheen, \"Sheen visibility\": V = 1 / ((1 + Λ(n·v) + Λ(n·l)) 4 (n·v)(n·l)), "
                       "Λ = lambda_sheen (Conty & Kulla 2017); not Ashikhmin's shortcut");
    Expr NoL = fb.param("NoL"), NoV = fb.param("NoV");
    std::vector<Expr> k;
    for (const char* name : {"a", "b", "c", "d", "e", "l_half"}) k.push_back(fb.param(name));
    std::vector<Expr> args_v{NoV}, args_l{NoL};
    args_v.insert(args_v.end(), k.begin(), k.end());
    args_l.insert(args_l.end(), k.begin(), k.end());
    Expr lv = fb.let("lambda_v", ir::call(sheen_lambda(), args_v));
    Expr ll = fb.let("lambda_l", ir::call(sheen_lambda(), args_l));
    return fb.returns(1.0 / ((1.0 + lv + ll) * (4.0 * NoV * NoL)));
  }();
  return f;
}

FunctionPtr sheen_albedo_series() {
  static const FunctionPtr f = [] {
    FunctionBuilder fb("sheen_E_series",
                       "KHR_materials_sheen, \"Albedo-scaling technique\": log(E + ε) of the sheen's directional "
                       "albedo on one piece of μ, Σ a_k T_k(x), x = μ^q mapped onto [−1, 1] "
                       "(scripts/fit_sheen_albedo.py)",
                       "a_k are the fit's coefficients at the material's sheen roughness; Clenshaw's recurrence "
                       "sums the Chebyshev series.");
    Expr x = fb.param("x");
    std::vector<Expr> a;
    for (int k = 0; k < kSheenAlbedoNodes; ++k) a.push_back(fb.param("a" + std::to_string(k)));
    // b_k = a_k + 2 x b_{k+1} − b_{k+2}, from the top; S = a_0 + x b_1 − b_2.
    const int n = kSheenAlbedoNodes - 1;
    Expr b1 = a[n], b2 = 0.0;
    for (int k = n - 1; k >= 1; --k) {
      Expr bk = fb.let("b" + std::to_string(k), k == n - 1 ? a[k] + 2.0 * x * b1 : a[k] + 2.0 * x * b1 - b2);
      b2 = b1;
      b1 = bk;
    }
    return fb.returns(a[0] + x * b1 - b2);
  }();
  return f;
}

}  // namespace terms
}  // namespace facet
