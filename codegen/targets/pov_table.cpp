// POV-Ray's fast route for a mesh with an isotropic material (--pov-route fast;
// shared/notes/povray.md §3.4, recipe B): no per-triangle data at all. An
// isotropic reflectance is a function of n·l, n·v and l·v; POV-Ray's own
// `slope { point_at … }` pattern gives the first two from its interpolated
// normal (N·d = −cos(π s)), and l·v depends on the hit point only. So the
// pigment is a table: a pigment_map over slope toward the light whose entries
// are pigment_maps over slope toward the eye, whose leaves are function
// pigments of the hit point with n·l and n·v fixed at the node's values.
// POV-Ray interpolates linearly in the angles between nodes: approximate, and
// the generator measures by how much (table_error).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "catalog/catalog.h"
#include "reference/interpreter.h"
#include "targets/pov_scene.h"

namespace facet::targets {

using ir::Expr;

namespace {

constexpr double kPiTable = 3.14159265358979323846;

// Node j of n: the slope value s and the cosine −cos(π s) = sin(π j / (2(n − 1))).
double node_s(int j, int n) { return 0.5 + 0.5 * double(j) / double(n - 1); }
double node_cos(int j, int n) { return std::sin(kPiTable * double(j) / (2.0 * double(n - 1))); }

// The inputs an isotropic lobe reads, from n·l, n·v and l·v (unit vectors:
// |l + v| = √(2 + 2 l·v), h = (l + v)/max(|l + v|, ε)); n·h is kept in [−1, 1]
// where the three cosines are not those of any three directions (a table node).
ShadingInputs table_inputs(double nl, double nv, double lv) {
  ShadingInputs in;
  in.NoL = nl, in.NoV = nv, in.LoV = lv;
  double hl = std::max(std::sqrt(std::max(2 + 2 * lv, 0.0)), kEpsilon);
  in.NoH = std::clamp((nl + nv) / hl, -1.0, 1.0);
  in.VoH = (1 + lv) / hl;
  return in;
}

// The body of a `pigment { … }`, for a pigment_map entry.
std::string pigment_body(const std::string& pigment) {
  size_t open = pigment.find('{'), close = pigment.rfind('}');
  return pigment.substr(open + 1, close - open - 1);
}

}  // namespace

// {P}Facet_Table{i}(x, y, z, NoL, NoV): light i's radiance of unit colour at the
// hit point for a normal with these cosines to the light and to the eye.
ir::FunctionPtr PovScene::table_function(PovShading& sh, size_t i) {
  const Light& l = s_.lights[i];
  const MaterialProgram& p = sh.program;
  ir::FunctionBuilder fb(fmt::format("Facet_Table{}", i), "");
  Expr x = fb.param("x"), y = fb.param("y"), z = fb.param("z"), nl = fb.param("NoL"), nv = fb.param("NoV");
  const Camera& c = s_.camera;
  const Vec3& e = c.position;
  const Vec3 toward = c.toward_eye(Vec3(0, 0, 0));  // orthographic: v is one direction
  Expr vx = toward.x, vy = toward.y, vz = toward.z, dv = 1.0;
  if (!c.orthographic) {
    vx = fb.let("Vx", e.x - x), vy = fb.let("Vy", e.y - y), vz = fb.let("Vz", e.z - z);
    dv = fb.let("Dv", ir::sqrt(vx * vx + vy * vy + vz * vz));
  }
  Expr lx = -l.direction.x, ly = -l.direction.y, lz = -l.direction.z, d = 1.0;
  if (l.type != Light::Type::Directional) {
    lx = fb.let("Lx", l.position.x - x), ly = fb.let("Ly", l.position.y - y), lz = fb.let("Lz", l.position.z - z);
    d = fb.let("D", ir::sqrt(lx * lx + ly * ly + lz * lz));
  }
  Expr lv = fb.let("LoV", (lx * vx + ly * vy + lz * vz) / (d * dv));
  Expr hl = p.uses_half_vector() ? fb.let("Hl", ir::max(ir::sqrt(ir::max(2.0 + 2.0 * lv, 0.0)), kEpsilon)) : Expr(1.0);
  std::vector<Expr> inputs;
  for (const auto& in : p.inputs) {
    if (in == "NoL") inputs.push_back(nl);
    else if (in == "NoV") inputs.push_back(nv);
    else if (in == "LoV") inputs.push_back(lv);
    else if (in == "NoH") inputs.push_back(ir::min(1.0, ir::max(-1.0, (nl + nv) / hl)));
    else if (in == "VoH") inputs.push_back((1.0 + lv) / hl);
    else throw std::logic_error("facet: a slope table has no input " + in);
  }
  Expr reflected = ir::call(p.reflectance, inputs);
  const Attenuation& a = l.attenuation;
  if (l.type != Light::Type::Directional) {
    if (a.law == Attenuation::Law::InverseSquare) reflected = ir::call(terms::attenuation_inverse_square(), {d}) * reflected;
    if (a.law == Attenuation::Law::Polynomial)
      reflected = ir::call(terms::attenuation_polynomial(), {d, a.constant, a.linear, a.quadratic}) * reflected;
    if (a.law == Attenuation::Law::InverseSquareRange)
      reflected = ir::call(terms::attenuation_inverse_square_range(), {d, a.range}) * reflected;
  }
  if (l.type == Light::Type::Spot)
    reflected = ir::call(terms::spot_cone(), {-(lx * l.direction.x + ly * l.direction.y + lz * l.direction.z) / d,
                                              std::cos(l.cutoff * kPiTable / 180), l.exponent}) *
                reflected;
  ir::FunctionPtr f = fb.returns(reflected);
  sh.printer.add_own(f);
  return f;
}

// Object o lit by light i through the table: `p` says the weight, transmit and factors.
std::string PovScene::table_pigment(size_t o, size_t i, PovPigment p, size_t width) {
  const PovShading& sh = shading(o);
  const Light& l = s_.lights[i];
  const std::string black = p.transmit > 0 ? fmt::format("rgbt <0, 0, 0, {}>", pov_number(p.transmit)) : "rgb 0";
  const std::string toward_light = l.type == Light::Type::Directional
                                       ? "slope { " + pov_vector(Vec3(0, 0, 0) - l.direction) + " }"
                                       : "slope { point_at " + pov_vector(l.position) + " }";
  const std::string toward_eye = s_.camera.orthographic
                                     ? "slope { " + pov_vector(s_.camera.toward_eye(Vec3(0, 0, 0))) + " }"
                                     : "slope { point_at " + pov_vector(s_.camera.position) + " }";
  const ir::FunctionPtr& f = sh.tables[i];
  std::string out = "pigment {\n  " + toward_light + "\n  pigment_map {\n    [0 " + black + "]\n";
  for (int j = 0; j < kTableNodes; ++j) {
    out += fmt::format("    [{} {}\n      pigment_map {{\n        [0 {}]\n", pov_number(node_s(j, kTableNodes)),
                       toward_eye, black);
    for (int k = 0; k < kTableNodes; ++k) {
      p.radiance = [&](int) {
        return ir::call(f, {var("x"), var("y"), var("z"), node_cos(j, kTableNodes), node_cos(k, kTableNodes)});
      };
      out += fmt::format("        [{}", pov_number(node_s(k, kTableNodes))) +
             pigment_body(pov_pigment(sh.printer, sh.dependent, p, width - 8)) + "]\n";
    }
    out += "      }]\n";
  }
  return out + "  }\n}\n";
}

// |table − exact| / max(1, |exact|) of the reflectance, per unit light: at the
// centre of every cell, for l·v = cos γ at 24 angles γ, where the three cosines
// are those of real directions. The largest, and the share of cells over 2e-3.
TableError table_error(const Material& m) {
  Reference ref(m);
  const int n = PovScene::kTableNodes;
  const size_t count = size_t(n);
  std::vector<double> c(count), angle(count);
  for (int j = 0; j < n; ++j) c[size_t(j)] = node_cos(j, n), angle[size_t(j)] = std::asin(c[size_t(j)]);
  TableError e;
  size_t cells = 0, over = 0;
  for (int g = 1; g < 24; ++g) {
    const double gamma = kPiTable * g / 24, lv = std::cos(gamma);
    std::vector<RGB> node(size_t(n * n));
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) node[size_t(j * n + k)] = ref.reflectance(table_inputs(c[size_t(j)], c[size_t(k)], lv));
    for (int j = 0; j + 1 < n; ++j)
      for (int k = 0; k + 1 < n; ++k) {
        // Elevations above the surface: the cell centre's angles to n are π/2 − them.
        const double el = (angle[size_t(j)] + angle[size_t(j + 1)]) / 2, ev = (angle[size_t(k)] + angle[size_t(k + 1)]) / 2;
        const double tl = kPiTable / 2 - el, tv = kPiTable / 2 - ev;
        if (gamma < std::abs(tl - tv) || gamma > tl + tv) continue;  // no such directions
        RGB exact = ref.reflectance(table_inputs(std::sin(el), std::sin(ev), lv));
        double cell = 0;
        for (size_t ch = 0; ch < 3; ++ch) {
          double mean = (node[size_t(j * n + k)][ch] + node[size_t((j + 1) * n + k)][ch] +
                         node[size_t(j * n + k + 1)][ch] + node[size_t((j + 1) * n + k + 1)][ch]) / 4;
          cell = std::max(cell, std::abs(mean - exact[ch]) / std::max(1.0, std::abs(exact[ch])));
        }
        e.worst = std::max(e.worst, cell);
        ++cells;
        over += cell > 2e-3;
      }
  }
  e.share_over = cells ? double(over) / double(cells) : 0;
  return e;
}

}  // namespace facet::targets
