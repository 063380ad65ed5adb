// KHR_materials_sheen's terms (README, "Implementation Notes"): the "Charlie" distribution and
// visibility of Conty & Kulla 2017, and E, the directional albedo the base is scaled by.
// E is a fit (scripts/fit_sheen_albedo.py; sheen_albedo_table.inc holds its coefficients): log(E + ε)
// as a Chebyshev series in μ^¼ or √μ, one per piece of μ, whose coefficients are Chebyshev series
// in √r, one per piece of sheen roughness r. A roughness of numbers has its r series summed when
// the code is generated (sheen_albedo_pieces), a roughness from an image at every pixel
// (sheen_albedo_r_pieces, catalog/specular.cpp gltf_sheen): the same E on every target, either way.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

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

constexpr int kRPieces = static_cast<int>(std::size(kSheenAlbedoRPieces)) - 1;
static_assert(kSheenAlbedoRPower == 0.5, "gltf_sheen sums the r series in √r");

// x = scale·v^q + offset maps [lo^q, hi^q] onto [−1, 1].
std::pair<double, double> chebyshev_map(double lo, double hi, double q) {
  const double a = std::pow(lo, q), b = std::pow(hi, q);
  return {2 / (b - a), -2 * a / (b - a) - 1};
}

}  // namespace

double sheen_albedo_worst_error() { return kSheenAlbedoWorstError; }

const std::vector<SheenAlbedoRPiece>& sheen_albedo_r_pieces() {
  static const std::vector<SheenAlbedoRPiece> pieces = [] {
    std::vector<SheenAlbedoRPiece> out;
    for (int rp = 0; rp < kRPieces; ++rp) {
      SheenAlbedoRPiece piece;
      piece.r_end = kSheenAlbedoRPieces[rp + 1];
      std::tie(piece.scale, piece.offset) = chebyshev_map(kSheenAlbedoRPieces[rp], piece.r_end, kSheenAlbedoRPower);
      for (const auto& mu_piece : kSheenAlbedoCoefficients[rp]) {
        std::vector<std::vector<double>> c;
        for (const auto& k : mu_piece) c.emplace_back(std::begin(k), std::end(k));
        piece.c.push_back(std::move(c));
      }
      out.push_back(std::move(piece));
    }
    return out;
  }();
  return pieces;
}

double sheen_albedo_r_min() { return kSheenAlbedoRPieces[0]; }

std::vector<SheenAlbedoPiece> sheen_albedo_pieces(double sheen_roughness) {
  // The r series at r: its piece, y on [−1, 1], T_j(y).
  const std::vector<SheenAlbedoRPiece>& r_pieces = sheen_albedo_r_pieces();
  const double r = std::clamp(sheen_roughness, sheen_albedo_r_min(), 1.0);
  size_t rp = 0;
  while (rp + 1 < r_pieces.size() && r >= r_pieces[rp].r_end) ++rp;
  const std::vector<double> t =
      chebyshev(r_pieces[rp].scale * std::pow(r, kSheenAlbedoRPower) + r_pieces[rp].offset, kSheenAlbedoRNodes - 1);
  std::vector<SheenAlbedoPiece> out;
  for (int p = 0; p < kMuPieces; ++p) {
    SheenAlbedoPiece piece;
    piece.mu_end = kSheenAlbedoMuPieces[p + 1];
    piece.power = kSheenAlbedoPowers[p];
    // The lobe takes m^q as √m or √√m (catalog/specular.cpp, gltf_sheen).
    if (piece.power != 0.5 && piece.power != 0.25) throw std::logic_error("sheen albedo: a piece's power is not ½ or ¼");
    std::tie(piece.scale, piece.offset) = chebyshev_map(kSheenAlbedoMuPieces[p], piece.mu_end, piece.power);
    for (const std::vector<double>& c : r_pieces[rp].c[p]) {
      double a = 0;
      for (int j = 0; j < kSheenAlbedoRNodes; ++j) a += c[j] * t[j];
      piece.coefficients.push_back(a);
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

std::array<std::pair<double, double>, 5> sheen_l_mix() {
  // The README's l(x, alpha_g): a … e, each mix(p, q, (1 − α)²).
  return {{{21.5473, 25.3245}, {3.82987, 3.32435}, {0.19823, 0.16801}, {-1.97760, -1.27393}, {-4.32054, -4.85967}}};
}

std::array<double, 6> sheen_visibility_constants(double alpha) {
  const double t = (1 - alpha) * (1 - alpha);
  std::array<double, 6> k{};
  const auto pq = sheen_l_mix();
  for (size_t i = 0; i < pq.size(); ++i) k[i] = pq[i].first + (pq[i].second - pq[i].first) * t;
  k[5] = k[0] / (1 + k[1] * std::pow(0.5, k[2])) + k[3] * 0.5 + k[4];
  return k;
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
