// POV-Ray 3.7 SDL.
//
// POV's own finish is used where it is exactly the catalog's model (Lambert,
// Phong and Blinn–Phong with a grey k_s; POV-compatible attenuation). Every
// other model is evaluated exactly in function pigments
// (shared/notes/povray.md, recipe A): the function receives the hit point, the
// generator knows each object's analytic normal, and the pigment holds the
// whole per-light radiance. `finish { diffuse 1 brilliance 0 }` then multiplies
// it by the light's colour and its shadow test, and nothing else.
//
// A pigment can encode one light. With several lights the scene either renders
// one light per pass (Declare=Facet_Light=i; the passes summed are exact) or,
// by default, puts one inset copy of each object in a light_group per light:
// one run, but the inset (1e-4 of the scene) moves shadow edges by a pixel and
// sharp highlights by up to about 1 % (measured; tests/unit/detection_test.cpp).
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/vec.h"
#include "targets/sweep_grid.h"
#include "targets/targets.h"
#include "targets/targets_internal.h"
#include "targets/templates.h"

namespace facet {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

namespace {

const char* kChannel[3] = {"R", "G", "B"};

std::string num(double v) {
  if (v == kPi) return "pi";
  if (v == 0) return "0";  // not "-0"
  return fmt::format("{}", v);
}

std::string vec(const Vec3& v) { return fmt::format("<{}, {}, {}>", num(v.x), num(v.y), num(v.z)); }
std::string rgb(const RGB& c) { return fmt::format("<{}, {}, {}>", num(c[0]), num(c[1]), num(c[2])); }
bool grey(const RGB& c) { return c[0] == c[1] && c[1] == c[2]; }
bool black(const RGB& c) { return c[0] == 0 && c[1] == 0 && c[2] == 0; }

// POV-Ray's keywords are lower case: identifiers that start upper case never clash.
std::string capital(const std::string& s) {
  std::string r = s;
  if (!r.empty()) r[0] = char(std::toupper(static_cast<unsigned char>(r[0])));
  return r;
}

// Prints IR as POV-Ray functions. Colors are scalar per channel: a function that
// reads a non-grey colour constant (itself or through a callee) is printed three
// times, suffixed _R, _G, _B.
class PovPrinter {
 public:
  // Functions in `own` (a material's lobes and reflectance) and every constant
  // get `prefix`, so several materials can share one scene file; catalog terms
  // are shared and printed once.
  PovPrinter(std::string prefix = "", std::set<const ir::Function*> own = {})
      : prefix_(std::move(prefix)), own_(std::move(own)) {}

  bool channel_dependent(const ir::FunctionPtr& f) {
    if (auto it = dependent_.find(f.get()); it != dependent_.end()) return it->second;
    bool dep = false;
    std::function<void(const NodePtr&)> walk = [&](const NodePtr& n) {
      if (n->op == Op::Constant && n->type == Type::Color && !grey(n->value)) dep = true;
      if (n->op == Op::Call && channel_dependent(n->callee)) dep = true;
      for (const auto& a : n->args) walk(a);
    };
    for (const auto& l : f->lets) walk(l.value.node());
    walk(f->result.node());
    dependent_[f.get()] = dep;
    return dep;
  }

  std::string name(const ir::FunctionPtr& f, int channel) {
    std::string n = own_.count(f.get()) ? prefix_ + capital(f->name) : capital(f->name);
    return channel_dependent(f) ? n + "_" + kChannel[channel] : n;
  }

  std::string constant_name(const NodePtr& c, int channel) const {
    std::string n = prefix_ + capital(c->name);
    return c->type == Type::Color && !grey(c->value) ? n + "_" + kChannel[channel] : n;
  }

  // Declarations of every constant `roots` read.
  std::string constants(const std::vector<NodePtr>& cs) const {
    std::string s;
    for (const auto& c : cs) {
      if (c->type == Type::Color && !grey(c->value)) {
        for (int ch = 0; ch < 3; ++ch) s += fmt::format("#declare {} = {};\n", constant_name(c, ch), num(c->value[ch]));
      } else {
        s += fmt::format("#declare {} = {};\n", constant_name(c, 0), num(c->value[0]));
      }
    }
    return s;
  }

  std::string condition(const NodePtr& n, int ch) {
    switch (n->op) {
      case Op::Lt: return "(" + expr(n->args[0], ch) + " < " + expr(n->args[1], ch) + ")";
      case Op::Le: return "(" + expr(n->args[0], ch) + " <= " + expr(n->args[1], ch) + ")";
      case Op::Gt: return "(" + expr(n->args[0], ch) + " > " + expr(n->args[1], ch) + ")";
      case Op::Ge: return "(" + expr(n->args[0], ch) + " >= " + expr(n->args[1], ch) + ")";
      case Op::And: return "(" + condition(n->args[0], ch) + " & " + condition(n->args[1], ch) + ")";
      case Op::Or: return "(" + condition(n->args[0], ch) + " | " + condition(n->args[1], ch) + ")";
      default: throw std::logic_error("facet: not a condition");
    }
  }

  // Precedence-aware: parentheses only where POV-Ray needs them, and on the
  // right operand at equal precedence so the evaluation order is the IR's.
  std::string expr(const NodePtr& n, int ch, int context = 0) {
    auto a = [&](int k, int c = 0) { return expr(n->args[k], ch, c); };
    int p = 9;
    std::string s;
    switch (n->op) {
      case Op::Literal:
        s = num(n->value[ch]);
        break;
      case Op::Constant: s = constant_name(n, ch); break;
      case Op::Arg:
      case Op::Local: s = local(n->name); break;
      case Op::Neg: p = 7; s = "-" + a(0, 8); break;
      case Op::Add: p = 5; s = a(0, 5) + " + " + a(1, 6); break;
      case Op::Sub: p = 5; s = a(0, 5) + " - " + a(1, 6); break;
      case Op::Mul: p = 6; s = a(0, 6) + " * " + a(1, 7); break;
      case Op::Div: p = 6; s = a(0, 6) + " / " + a(1, 7); break;
      case Op::Min: s = "min(" + a(0) + ", " + a(1) + ")"; break;
      case Op::Max: s = "max(" + a(0) + ", " + a(1) + ")"; break;
      case Op::Clamp: s = "min(max(" + a(0) + ", " + a(1) + "), " + a(2) + ")"; break;
      case Op::Sqrt: s = "sqrt(" + a(0) + ")"; break;
      case Op::Exp: s = "exp(" + a(0) + ")"; break;
      case Op::Pow: s = "pow(" + a(0) + ", " + a(1) + ")"; break;
      case Op::Acos: s = "acos(" + a(0) + ")"; break;
      case Op::Atan2: s = "atan2(" + a(0) + ", " + a(1) + ")"; break;
      case Op::Abs: s = "abs(" + a(0) + ")"; break;
      case Op::Sin: s = "sin(" + a(0) + ")"; break;
      case Op::Cos: s = "cos(" + a(0) + ")"; break;
      case Op::Floor: s = "floor(" + a(0) + ")"; break;
      case Op::Step: s = "(" + a(1) + " >= " + a(0) + ")"; break;
      case Op::Select: {
        // select(A, B, C[, D]): A < 0 → B; A = 0 → C; A > 0 → D (or C).
        const NodePtr& c = n->args[0];
        std::string t = a(1), f = a(2);
        bool simple = c->op != Op::And && c->op != Op::Or;
        std::string x;
        if (simple) {
          const NodePtr& rhs = c->args[1];
          bool zero = rhs->op == Op::Literal && rhs->value[ch] == 0;
          x = zero ? expr(c->args[0], ch) : expr(c->args[0], ch, 5) + " - " + expr(rhs, ch, 6);
        }
        switch (c->op) {
          case Op::Lt: s = fmt::format("select({}, {}, {})", x, t, f); break;
          case Op::Le: s = fmt::format("select({}, {}, {}, {})", x, t, t, f); break;
          case Op::Gt: s = fmt::format("select({}, {}, {}, {})", x, f, f, t); break;
          case Op::Ge: s = fmt::format("select({}, {}, {})", x, f, t); break;
          default: s = fmt::format("select({} - 0.5, {}, {})", condition(c, ch), f, t);
        }
        break;
      }
      case Op::Call: {
        s = name(n->callee, ch) + "(";
        for (size_t k = 0; k < n->args.size(); ++k) s += (k ? ", " : "") + a(int(k));
        s += ")";
        break;
      }
      default: throw std::logic_error("facet: the POV-Ray printer cannot print this operation");
    }
    if (n->op == Op::Literal && n->value[ch] < 0) p = 7;
    return p < context ? "(" + s + ")" : s;
  }

  // One function per let: F(params) calls F__1(params, let1), which calls
  // F__2(params, let1, let2)…, since POV-Ray functions have no local variables.
  std::string function(const ir::FunctionPtr& f) {
    std::string out;
    int channels = channel_dependent(f) ? 3 : 1;
    for (int ch = 0; ch < channels; ++ch) {
      std::string base = name(f, ch);
      std::vector<std::string> params;
      for (const auto& p : f->params) params.push_back(local(p.name));
      auto sig = [&](size_t k) {
        std::string s;
        for (size_t i = 0; i < params.size() + k; ++i)
          s += (i ? ", " : "") + (i < params.size() ? params[i] : local(f->lets[i - params.size()].name));
        return s;
      };
      auto step_name = [&](size_t k) { return k == 0 ? base : fmt::format("{}__{}", base, k); };
      std::vector<std::string> steps;
      for (size_t k = 0; k <= f->lets.size(); ++k) {
        std::string body;
        if (k == f->lets.size()) {
          body = expr(f->result.node(), ch);
        } else {
          body = step_name(k + 1) + "(" + sig(k) + (sig(k).empty() ? "" : ", ") + expr(f->lets[k].value.node(), ch) + ")";
        }
        steps.push_back(fmt::format("#declare {} = function({}) {{ {} }}\n", step_name(k), sig(k), body));
      }
      out += comment(f->citation);
      if (!f->doc.empty()) out += comment(f->doc);
      for (size_t k = steps.size(); k-- > 0;) out += steps[k];
    }
    return out;
  }

  static std::string comment(const std::string& text) {
    std::string s, line;
    std::istringstream in(text);
    while (std::getline(in, line)) s += "// " + line + "\n";
    return s;
  }

 private:
  static std::string local(const std::string& n) { return capital(n); }
  std::string prefix_;
  std::set<const ir::Function*> own_;
  std::map<const ir::Function*, bool> dependent_;
};

// ---------------------------------------------------------------- the plan

// POV-Ray's attenuation matches the catalog's law exactly (povray.md §2).
bool native_attenuation(const Light& l) {
  if (l.type == Light::Type::Directional) return true;
  const Attenuation& a = l.attenuation;
  switch (a.law) {
    case Attenuation::Law::None:
    case Attenuation::Law::InverseSquare: return true;
    case Attenuation::Law::Polynomial:
      // min(1, ·) never bites when c1 ≥ 1; fade has one power term.
      return a.constant >= 1 && (a.linear == 0 || a.quadratic == 0);
  }
  return false;
}

// Why a lobe is not a POV-Ray finish, or "" when it is exactly one.
std::string lobe_native(const std::optional<ModelSpec>& lobe, bool specular) {
  if (!lobe) return "";
  const ModelSpec& s = *lobe;
  auto toon = s.values.find("toon");
  if (toon != s.values.end() && toon->second.model) return "the toon modifier is not a POV-Ray finish";
  if (!specular) return s.def->name == "lambert" ? "" : s.def->name + " is not a POV-Ray finish";
  if (s.def->name != "phong" && s.def->name != "blinn_phong") return s.def->name + " is not a POV-Ray finish";
  if (s.at("approximation").choice != "none") return "Schlick's approximation is not a POV-Ray finish";
  if (!grey(s.at("color").rgb)) return "POV-Ray highlights take a grey k_s only";
  return "";
}

std::string material_native(const Material& m) {
  std::string why = lobe_native(m.diffuse, false);
  return why.empty() ? lobe_native(m.specular, true) : why;
}

}  // namespace

PovPlan pov_plan(const Scene& s, const Material* fallback) {
  PovPlan plan;
  for (size_t i = 0; i < s.objects.size() && plan.reason.empty(); ++i) {
    if (s.objects[i].type == Object::Type::Mesh)
      plan.reason = "meshes are shaded by function pigments (exact interpolated normals)";
    else
      plan.reason = material_native(s.material_of(i, fallback));
  }
  for (const auto& l : s.lights)
    if (plan.reason.empty() && !native_attenuation(l)) plan.reason = "this attenuation law is not a POV-Ray fade";
  plan.native = plan.reason.empty();
  // Function pigments: a pass per light, and one for the emission (m_a ⊗ A + m_e).
  bool emits = false;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Material& m = s.material_of(i, fallback);
    for (int c = 0; c < 3; ++c) emits |= m.ambient[size_t(c)] * s.ambient[size_t(c)] + m.emission[size_t(c)] != 0;
  }
  plan.passes = plan.native ? 1 : std::max(1, int(s.lights.size()) + (emits ? 1 : 0));
  return plan;
}

PovPlan pov_plan(const Material& m, const Scene& s) { return pov_plan(s, &m); }

namespace {

// ---------------------------------------------------------------- scene frame

// One material of the scene: its program and the printer with its prefix.
struct Shading {
  const Material* material;
  MaterialProgram program;
  PovPrinter printer;
  std::string prefix;  // "" when the scene has one material
  bool dependent;      // reflectance differs per channel: three functions
  int channels() const { return dependent ? 3 : 1; }
  std::string suffix(int ch) const { return dependent ? std::string("_") + kChannel[ch] : ""; }
  RGB emission(const Scene& s) const {
    RGB e;
    for (int i = 0; i < 3; ++i) e[i] = material->ambient[i] * s.ambient[i] + material->emission[i];
    return e;
  }
};

class PovScene {
 public:
  PovScene(const Scene& s, const Material* fallback, const std::string& source)
      : s_(s), source_(source), plan_(pov_plan(s, fallback)) {
    std::vector<const Material*> distinct;
    for (size_t i = 0; i < s.objects.size(); ++i) {
      const Material* m = &s.material_of(i, fallback);
      auto it = std::find(distinct.begin(), distinct.end(), m);
      shading_of_.push_back(size_t(it - distinct.begin()));
      if (it == distinct.end()) distinct.push_back(m);
    }
    if (distinct.empty() && fallback) distinct.push_back(fallback);
    std::set<std::string> prefixes;
    for (const Material* m : distinct) {
      auto sh = std::make_unique<Shading>();
      sh->material = m;
      sh->program = compile(*m);
      if (distinct.size() > 1) {
        sh->prefix = capital(identifier(m->name)) + "_";
        while (!prefixes.insert(sh->prefix).second) sh->prefix = "M" + sh->prefix;
      }
      std::set<const ir::Function*> own = {sh->program.reflectance.get()};
      if (sh->program.diffuse) own.insert(sh->program.diffuse.get());
      if (sh->program.specular) own.insert(sh->program.specular.get());
      sh->printer = PovPrinter(sh->prefix, own);
      sh->dependent = sh->printer.channel_dependent(sh->program.reflectance);
      shadings_.push_back(std::move(sh));
    }
    double r = length(s.camera.position);
    for (const auto& o : s.objects) {
      Vec3 c;
      double rad;
      o.bounds(c, rad);
      r = std::max(r, length(c) + rad);
    }
    scale_ = std::max(r, 1.0);
  }

  std::string render() {
    std::string out = header();
    out += "#version 3.7;\n";
    out += "global_settings { assumed_gamma 1.0 ambient_light 0 }  // linear: render with File_Gamma=1.0\n\n";
    out += "#ifndef (Facet_Light) #declare Facet_Light = -1; #end        // -1: every light; i: light i alone\n";
    out += "#ifndef (Facet_Exposure) #declare Facet_Exposure = 1; #end  // scales every radiance (keeps PNGs below 1)\n";
    out += fmt::format("#declare Facet_Passes = {};  // renders with Facet_Light = 0 … {} sum to the exact image\n\n",
                       plan_.native ? 1 : plan_.passes, plan_.native ? 0 : plan_.passes - 1);
    out += camera();
    if (plan_.native) out += native();
    else out += functions() + frames() + lit_objects();
    return out;
  }

  // The robustness sweep (facet/sweep.h): each pixel centre of a unit square is a
  // direction set of the grid; each channel shows whether that channel of the
  // reflectance is finite and ≥ 0 (POV-Ray would render a NaN black, like a 0).
  std::string sweep() {
    const Shading& sh = *shadings_.front();
    std::string out = header() + "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n";
    out += "camera { orthographic location <0.5, 0.5, -1> direction z right x up y }\n\n";
    out += functions() + frames();
    out += "// ---- The sweep grid\n";
    PovPrinter grid;
    for (const auto& f : ir::dependencies(sweep_grid())) out += grid.function(f) + "\n";
    out += "#declare Facet_Ok = function(V) { (V >= 0) & (V <= 1e300) }\n";
    std::string args;
    for (const char* v : {"n", "l", "v"})
      for (const char* c : {"x", "y", "z"}) args += fmt::format("{}Sweep_{}_{}(x, y)", args.empty() ? "" : ", ", v, c);
    out += "polygon { 5, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0>, <0, 0, 0>\n  pigment { average pigment_map {\n";
    for (int ch = 0; ch < 3; ++ch) {
      out += fmt::format("    [1 function {{ Facet_Ok(Facet_Reflect{}({})) }} color_map {{ [0 rgb 0] [1 rgb {}] }}]\n",
                         sh.suffix(sh.dependent ? ch : 0), args,
                         ch == 0 ? "<3, 0, 0>" : ch == 1 ? "<0, 3, 0>" : "<0, 0, 3>");
    }
    out += "  } }\n  finish { ambient 0 diffuse 0 specular 0 phong 0 emission 1 }\n}\n";
    return out;
  }

  std::string library() {
    const Shading& sh = *shadings_.front();
    const Material& m = *sh.material;
    std::string out = header();
    if (plan_.native) {
      out += "// POV-Ray's own finish is this model exactly. Use the texture with plain light sources;\n";
      out += "// attenuation: fade_distance 0 fade_power 2 is 1/d² (facet's inverse_square).\n";
      out += fmt::format("#declare Facet_{}_Texture = texture {{ {} }}\n", capital(identifier(m.name)),
                         native_texture(m, 1));
      RGB e = sh.emission(s_);
      if (!black(e)) {
        out += "// The emissive part (m_a ⊗ A + m_e) as a layer over it:\n";
        out += fmt::format("#declare Facet_{}_Emission = {}\n", capital(identifier(m.name)), emission_texture(e, 2, 0.5));
      }
      return out;
    }
    out += "// This model is not a POV-Ray finish: it is evaluated exactly in function pigments, which\n";
    out += "// see only the hit point. Your scene must provide, per object and light:\n";
    out += "//   * the object's unit normal as three functions of (x, y, z), world space (texture after transforms);\n";
    out += "//   * the light: a point light's position (attenuation and spot go into the pigment);\n";
    out += "//   * the eye position.\n";
    out += "// Facet_Pigment_Point(NX, NY, NZ, LightPosition, Eye, Scale) builds the pigment for one point light;\n";
    out += "// light the object with that light alone (light_group) and finish { Facet_Finish }. Scale: the pigment\n";
    out += "// is exact up to 1/Scale (use the light's brightest channel).\n\n";
    out += functions() + frames();
    out += R"(#declare Facet_Finish = finish { ambient 0 emission 0 diffuse 1 brilliance 0 specular 0 phong 0 }
#macro Facet_Pigment_Point(NX, NY, NZ, LightPosition, Eye, Scale)
  #local Lp = LightPosition; #local E = Eye;
)";
    if (sh.dependent) {
      out += "  pigment { average pigment_map {\n";
      for (int ch = 0; ch < 3; ++ch) {
        out += fmt::format("    [1 function {{ max(0, min(1, Facet_Point_Shade_{}(x, y, z, NX(x, y, z), NY(x, y, z), "
                           "NZ(x, y, z), Lp.x, Lp.y, Lp.z, E.x, E.y, E.z) * Scale)) }} color_map {{ [0 rgb 0] [1 rgb "
                           "{}] }}]\n",
                           kChannel[ch], ch == 0 ? "<3/Scale, 0, 0>" : ch == 1 ? "<0, 3/Scale, 0>" : "<0, 0, 3/Scale>");
      }
      out += "  } }\n";
    } else {
      out += "  pigment { function { max(0, min(1, Facet_Point_Shade(x, y, z, NX(x, y, z), NY(x, y, z), NZ(x, y, z), "
             "Lp.x, Lp.y, Lp.z, E.x, E.y, E.z) * Scale)) } color_map { [0 rgb 0] [1 rgb 1/Scale] } }\n";
    }
    out += "#end\n";
    for (int ch = 0; ch < sh.channels(); ++ch) {
      out += fmt::format(
          "#declare Facet_Point_Shade{0}__1 = function(Nx, Ny, Nz, Lx, Ly, Lz, Vx, Vy, Vz, D, Dv) {{ "
          "Facet_Reflect{0}(Nx, Ny, Nz, Lx/D, Ly/D, Lz/D, Vx/Dv, Vy/Dv, Vz/Dv) }}\n"
          "#declare Facet_Point_Shade{0} = function(x, y, z, Nx, Ny, Nz, Px, Py, Pz, Ex, Ey, Ez) {{ "
          "Facet_Point_Shade{0}__1(Nx, Ny, Nz, Px-x, Py-y, Pz-z, Ex-x, Ey-y, Ez-z, "
          "sqrt((Px-x)*(Px-x) + (Py-y)*(Py-y) + (Pz-z)*(Pz-z)), sqrt((Ex-x)*(Ex-x) + (Ey-y)*(Ey-y) + (Ez-z)*(Ez-z))) }}\n",
          sh.suffix(ch));
    }
    return out;
  }

 private:
  std::string header() {
    std::string names;
    for (const auto& sh : shadings_) names += (names.empty() ? "" : ", ") + sh->material->name;
    std::string out = fmt::format("// facet {} \"{}\" — POV-Ray 3.7 {}\n", shadings_.size() > 1 ? "materials" : "material",
                                  names, plan_.native ? "(native finish)" : "(function pigments)");
    out += fmt::format("// Generated by facet {} from {}. Edit the material, not this file.\n//\n", FACET_VERSION,
                       source_);
    for (const auto& sh : shadings_) out += describe_material(*sh->material, "//");
    out += fmt::format("// Scene \"{}\". Render linear and unantialiased:\n", s_.name);
    out += "//   povray +I<this file> +O<image>.png +W256 +H256 -A +FN16 File_Gamma=1.0\n";
    if (plan_.native) {
      out += "// POV-Ray's own finish is this model: every light in one render is exact.\n";
    } else if (plan_.passes > 1) {
      bool meshes = std::any_of(s_.objects.begin(), s_.objects.end(),
                                [](const Object& o) { return o.type == Object::Type::Mesh; });
      out += fmt::format("// Function pigments hold one light each. Exact: render with Declare=Facet_Light=i for i = 0..{}\n"
                         "// (the lights{}; Facet_Passes below) and sum the images. Facet_Light=-1 (default) renders\n"
                         "// everything at once through light_group copies inset by 1e-4 of the scene's size, and the\n"
                         "// inset moves what each copy sees: shadow edges shift by a pixel, and sharp highlights\n"
                         "// by up to 1 % (facet measured Ward αx = 0.1 at 0.5 % on 1 % of its pixels){}.\n",
                         plan_.passes - 1, plan_.passes > int(s_.lights.size()) ? ", then the emission" : "",
                         meshes ? "; on meshes about\n// 1 % of the pixels are off by up to 15 %. Use the passes for "
                                  "anything you compare"
                                : "");
    } else {
      out += "// Function pigments evaluate the model exactly (to 16-bit output precision).\n";
    }
    if (!plan_.native) out += "// (" + plan_.reason + ")\n";
    return out + "\n";
  }

  std::string camera() {
    const Camera& c = s_.camera;
    return fmt::format(
        "// facet's world is right-handed: the negative right vector makes POV-Ray's camera right-handed too.\n"
        "camera {{\n"
        "  perspective\n"
        "  location {}\n"
        "  right -x*image_width/image_height\n"
        "  up y\n"
        "  sky {}\n"
        "  angle 2*degrees(atan(image_width/image_height*tan(radians({}/2))))  // vertical field of view {}°\n"
        "  look_at {}\n"
        "}}\n\n",
        vec(c.position), vec(c.up), num(c.fov), num(c.fov), vec(c.look_at));
  }

  std::string light_source(const Light& l, const std::string& extra = "", double scale = 1) {
    bool parallel = l.type == Light::Type::Directional;
    return fmt::format("light_source {{ {} color rgb {}*{}Facet_Exposure{}{} }}",
                       parallel ? vec(Vec3(0, 0, 0) - l.direction * 1e5) : vec(l.position), rgb(l.color),
                       scale == 1 ? "" : num(scale) + "*", parallel ? " parallel point_at <0, 0, 0>" : "", extra);
  }

  static std::string emission_texture(const RGB& e, double weight, double t) {
    return fmt::format("texture {{ pigment {{ rgbt <{}, {}, {}, {}> }} finish {{ ambient 0 emission Facet_Exposure "
                       "diffuse 0 specular 0 phong 0 }} }}",
                       num(weight * e[0]), num(weight * e[1]), num(weight * e[2]), num(t));
  }

  // The geometry of object o with `body` inside; `shrink` (relative to the scene) insets a copy.
  std::string object(size_t o, double shrink, const std::string& body, const std::string& modifiers) {
    const Object& obj = s_.objects[o];
    if (obj.type == Object::Type::Sphere)
      return fmt::format("sphere {{ {}, {}{}{}}}", vec(obj.center), num(obj.radius - shrink * scale_), body, modifiers);
    if (obj.type == Object::Type::Plane) {
      Vec3 u, v;
      obj.plane_axes(u, v);
      Vec3 c = obj.point - obj.normal * (shrink * scale_);
      Vec3 p0 = c + (u + v) * obj.size, p1 = c + (v - u) * obj.size, p2 = c - (u + v) * obj.size,
           p3 = c + (u - v) * obj.size;
      return fmt::format("polygon {{ 5, {}, {}, {}, {}, {}{}{}}}", vec(p0), vec(p1), vec(p2), vec(p3), vec(p0), body,
                         modifiers);
    }
    // A mesh: `body` is its texture_list; each face uses its own texture.
    const Mesh& m = *obj.mesh;
    std::string out = fmt::format("mesh2 {{  // {}\n  vertex_vectors {{ {}", obj.name, m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i)
      out += (i % 4 == 0 ? ",\n    " : ", ") + vec(m.positions[i] - m.normals[i] * (shrink * scale_));
    out += fmt::format("\n  }}\n  normal_vectors {{ {}", m.normals.size());
    for (size_t i = 0; i < m.normals.size(); ++i) out += (i % 4 == 0 ? ",\n    " : ", ") + vec(m.normals[i]);
    out += "\n  }\n" + body;
    out += fmt::format("  face_indices {{ {}", m.triangles.size());
    for (size_t i = 0; i < m.triangles.size(); ++i) {
      const auto& t = m.triangles[i];
      out += fmt::format("{}<{}, {}, {}>{}", i % 6 == 0 ? ",\n    " : ", ", t[0], t[1], t[2],
                         body.empty() ? "" : fmt::format(", {}", i));
    }
    return out + "\n  }\n" + modifiers + "}";
  }

  // ---- native route

  static std::string native_texture(const Material& m, double weight) {
    std::string finish = fmt::format("ambient 0 emission 0 diffuse {} brilliance 1", num(m.diffuse ? weight : 0));
    if (m.specular) {
      double ks = m.specular->at("color").rgb[0] * weight;
      double n = m.specular->at("n").number;
      if (m.specular->def->name == "phong") finish += fmt::format(" phong {} phong_size {}", num(ks), num(n));
      else finish += fmt::format(" specular {} roughness {}", num(ks), num(1.0 / n));
    } else {
      finish += " specular 0 phong 0";
    }
    RGB kd = m.diffuse ? m.diffuse->at("color").rgb : RGB{0, 0, 0};
    return fmt::format("pigment {{ rgb {} }} finish {{ {} }}", rgb(kd), finish);
  }

  std::string native_light(size_t i) {
    const Light& l = s_.lights[i];
    if (l.type == Light::Type::Directional) return light_source(l) + fmt::format("  // light {}: directional\n", i);
    const Attenuation& a = l.attenuation;
    double scale = 1;
    std::string extra;
    if (a.law == Attenuation::Law::InverseSquare) extra += " fade_distance 0 fade_power 2";
    if (a.law == Attenuation::Law::Polynomial) {
      if (a.linear == 0 && a.quadratic == 0) {
        scale = 1 / a.constant;
      } else if (a.quadratic == 0) {  // 2/(1 + d/fd) · C/(2 c1) = C/(c1 + c2 d)
        scale = 1 / (2 * a.constant);
        extra += fmt::format(" fade_distance {} fade_power 1", num(a.constant / a.linear));
      } else {  // 2/(1 + (d/fd)²) · C/(2 c1) = C/(c1 + c3 d²)
        scale = 1 / (2 * a.constant);
        extra += fmt::format(" fade_distance {} fade_power 2", num(std::sqrt(a.constant / a.quadratic)));
      }
    }
    if (l.type == Light::Type::Spot) {
      extra += fmt::format(" spotlight point_at {} radius {} falloff {} tightness {}", vec(l.position + l.direction),
                           num(l.cutoff), num(l.cutoff), num(l.exponent));
    }
    return light_source(l, extra, scale) + fmt::format("  // light {}\n", i);
  }

  std::string native() {
    std::string out = "// ---- Lights (POV-Ray's attenuation is the catalog's law here)\n";
    for (size_t i = 0; i < s_.lights.size(); ++i) out += native_light(i);
    out += "\n// ---- Objects\n";
    for (size_t o = 0; o < s_.objects.size(); ++o) {
      const Shading& sh = *shadings_[shading_of_[o]];
      RGB e = sh.emission(s_);
      std::string tex = black(e) ? fmt::format("texture {{ {} }}", native_texture(*sh.material, 1))
                                 : fmt::format("texture {{ {} }}\n  {}", native_texture(*sh.material, 2),
                                               emission_texture(e, 2, 0.5));
      out += object(o, 0, "\n  " + tex + "\n", "") + "\n";
    }
    return out;
  }

  // ---- function route

  std::string functions() {
    std::string out;
    for (const auto& sh : shadings_) {
      out += fmt::format("// ---- Material constants{}\n",
                         sh->prefix.empty() ? "" : " of \"" + sh->material->name + "\"");
      out += sh->printer.constants(sh->program.constants());
    }
    out += "\n// ---- Terms (one function per term of the model catalog)\n";
    std::set<const ir::Function*> printed;
    for (const auto& sh : shadings_) {
      for (const auto& f : sh->program.functions()) {
        if (!printed.insert(f.get()).second) continue;
        out += sh->printer.function(f) + "\n";
      }
    }
    return out;
  }

  // {P}Facet_Reflect(N, L, V): the catalog's inputs from unit vectors, with the tangent rule.
  std::string frames() {
    std::string out = "// ---- Shading frame: unit n, l, v → Reflectance's inputs\n";
    const char* nlv = "Nx, Ny, Nz, Lx, Ly, Lz, Vx, Vy, Vz";
    for (const auto& sh : shadings_) {
      const MaterialProgram& p = sh->program;
      for (int ch = 0; ch < sh->channels(); ++ch) {
        std::string name = sh->prefix + "Facet_Reflect" + sh->suffix(ch);
        std::string refl = sh->printer.name(p.reflectance, ch);
        std::map<std::string, std::string> dots = {
            {"NoL", "Nx*Lx + Ny*Ly + Nz*Lz"}, {"NoV", "Nx*Vx + Ny*Vy + Nz*Vz"}, {"LoV", "Lx*Vx + Ly*Vy + Lz*Vz"},
            {"LoT", "Lx*Tx + Ly*Ty + Lz*Tz"}, {"VoT", "Vx*Tx + Vy*Ty + Vz*Tz"},
            // b = n × t
            {"LoB", "Lx*(Ny*Tz - Nz*Ty) + Ly*(Nz*Tx - Nx*Tz) + Lz*(Nx*Ty - Ny*Tx)"},
            {"VoB", "Vx*(Ny*Tz - Nz*Ty) + Vy*(Nz*Tx - Nx*Tz) + Vz*(Nx*Ty - Ny*Tx)"},
            // h = (l + v) / Hl, Hl = max(|l + v|, ε) (catalog.h, Input)
            {"NoH", "(Nx*(Lx+Vx) + Ny*(Ly+Vy) + Nz*(Lz+Vz))/Hl"},
            {"VoH", "(Vx*(Lx+Vx) + Vy*(Ly+Vy) + Vz*(Lz+Vz))/Hl"},
            {"HoT", "((Lx+Vx)*Tx + (Ly+Vy)*Ty + (Lz+Vz)*Tz)/Hl"},
            {"HoB", "((Lx+Vx)*(Ny*Tz - Nz*Ty) + (Ly+Vy)*(Nz*Tx - Nx*Tz) + (Lz+Vz)*(Nx*Ty - Ny*Tx))/Hl"}};
        std::string args;
        for (const auto& in : p.inputs) args += (args.empty() ? "" : ", ") + dots[in];
        // The function that calls the reflectance; with half-vector inputs it takes
        // Hl from one more level, as POV-Ray functions have no local variables.
        auto reflect_level = [&](const std::string& fname, const std::string& sig) {
          if (!p.uses_half_vector()) return fmt::format("#declare {} = function({}) {{ {}({}) }}\n", fname, sig, refl, args);
          return fmt::format(
              "#declare {0}__h = function({1}, Hl) {{ {2}({3}) }}\n"
              "#declare {0} = function({1}) {{ {0}__h({1}, max(sqrt((Lx+Vx)*(Lx+Vx) + (Ly+Vy)*(Ly+Vy) + "
              "(Lz+Vz)*(Lz+Vz)), {4})) }}\n",
              fname, sig, refl, args, num(kEpsilon));
        };
        if (!p.uses_tangent()) {
          out += reflect_level(name, nlv);
          continue;
        }
        Vec3 a = normalize(Vec3(sh->material->tangent_axis));
        // t = normalize(axis × n), or x̂ × n = (0, −nz, ny) where |axis × n| < ε.
        out += reflect_level(name + "__3", std::string(nlv) + ", Tx, Ty, Tz");
        out += fmt::format("#declare {0}__2 = function({1}, Cx, Cy, Cz, Len) {{ {0}__3({1}, Cx/Len, Cy/Len, Cz/Len) }}\n",
                           name, nlv);
        out += fmt::format(
            "#declare {0}__1 = function({1}, Cx, Cy, Cz, Len) {{ select(Len - 1e-4, {0}__2({1}, 0, -Nz, Ny, "
            "sqrt(Nz*Nz + Ny*Ny)), {0}__2({1}, Cx, Cy, Cz, Len)) }}\n",
            name, nlv);
        out += fmt::format(
            "#declare {0} = function({1}) {{ {0}__1({1}, {2}*Nz - {3}*Ny, {3}*Nx - {4}*Nz, {4}*Ny - {2}*Nx, "
            "sqrt(({2}*Nz - {3}*Ny)*({2}*Nz - {3}*Ny) + ({3}*Nx - {4}*Nz)*({3}*Nx - {4}*Nz) + "
            "({4}*Ny - {2}*Nx)*({4}*Ny - {2}*Nx))) }}\n",
            name, nlv, num(a.y), num(a.z), num(a.x));
      }
    }
    return out + "\n";
  }

  // {P}Facet_Light{i}(x, y, z, Nx, Ny, Nz): the radiance of light i of unit colour
  // at a point with unit normal N, seen from the camera: att(d) · spot · reflectance.
  std::string light_function(const Shading& sh, size_t i, int ch) {
    const Light& l = s_.lights[i];
    std::string reflect = sh.prefix + "Facet_Reflect" + sh.suffix(ch);
    std::string name = fmt::format("{}Facet_Light{}{}", sh.prefix, i, sh.suffix(ch));
    Vec3 e = s_.camera.position;
    std::string view = fmt::format("sqrt(({0}-x)*({0}-x) + ({1}-y)*({1}-y) + ({2}-z)*({2}-z))", num(e.x), num(e.y),
                                   num(e.z));
    std::string v = fmt::format("({}-x)/Dv, ({}-y)/Dv, ({}-z)/Dv", num(e.x), num(e.y), num(e.z));
    std::string out;
    if (l.type == Light::Type::Directional) {
      Vec3 d = -l.direction;
      out += fmt::format("#declare {0}__1 = function(x, y, z, Nx, Ny, Nz, Dv) {{ {1}(Nx, Ny, Nz, {2}, {3}, {4}, {5}) }}\n",
                         name, reflect, num(d.x), num(d.y), num(d.z), v);
      out += fmt::format("#declare {0} = function(x, y, z, Nx, Ny, Nz) {{ {0}__1(x, y, z, Nx, Ny, Nz, {1}) }}\n", name,
                         view);
      return out;
    }
    const Vec3& p = l.position;
    std::string factor;
    const Attenuation& a = l.attenuation;
    if (a.law == Attenuation::Law::InverseSquare) factor = "Attenuation_inverse_square(D) * ";
    if (a.law == Attenuation::Law::Polynomial)
      factor = fmt::format("Attenuation_polynomial(D, {}, {}, {}) * ", num(a.constant), num(a.linear), num(a.quadratic));
    if (l.type == Light::Type::Spot) {
      factor += fmt::format("Spot_cone(-(Lx*{} + Ly*{} + Lz*{}), {}, {}) * ", num(l.direction.x), num(l.direction.y),
                            num(l.direction.z), num(std::cos(l.cutoff * kPi / 180)), num(l.exponent));
    }
    out += fmt::format(
        "#declare {0}__2 = function(Nx, Ny, Nz, Lx, Ly, Lz, Vx, Vy, Vz, D) {{ {1}{2}(Nx, Ny, Nz, Lx, Ly, Lz, Vx, Vy, Vz) }}\n",
        name, factor, reflect);
    out += fmt::format(
        "#declare {0}__1 = function(x, y, z, Nx, Ny, Nz, D, Dv) {{ {0}__2(Nx, Ny, Nz, ({1}-x)/D, ({2}-y)/D, ({3}-z)/D, "
        "{4}, D) }}\n",
        name, num(p.x), num(p.y), num(p.z), v);
    out += fmt::format(
        "#declare {0} = function(x, y, z, Nx, Ny, Nz) {{ {0}__1(x, y, z, Nx, Ny, Nz, sqrt(({1}-x)*({1}-x) + "
        "({2}-y)*({2}-y) + ({3}-z)*({3}-z)), {4}) }}\n",
        name, num(p.x), num(p.y), num(p.z), view);
    return out;
  }

  // Facet_Object{o}_Light{i}: light i on object o. Spheres and squares take
  // (x, y, z); meshes take (x, y, z) and the unnormalized interpolated normal.
  std::string object_function(size_t o, size_t i, int ch) {
    const Object& obj = s_.objects[o];
    const Shading& sh = *shadings_[shading_of_[o]];
    std::string name = fmt::format("Facet_Object{}_Light{}{}", o, i, sh.suffix(ch));
    std::string light = fmt::format("{}Facet_Light{}{}", sh.prefix, i, sh.suffix(ch));
    if (obj.type == Object::Type::Plane) {
      return fmt::format("#declare {} = function(x, y, z) {{ {}(x, y, z, {}, {}, {}) }}\n", name, light,
                         num(obj.normal.x), num(obj.normal.y), num(obj.normal.z));
    }
    if (obj.type == Object::Type::Mesh) {
      return fmt::format(
          "#declare {0}__1 = function(x, y, z, Mx, My, Mz, Len) {{ {1}(x, y, z, Mx/Len, My/Len, Mz/Len) }}\n"
          "#declare {0} = function(x, y, z, Mx, My, Mz) {{ {0}__1(x, y, z, Mx, My, Mz, sqrt(Mx*Mx + My*My + Mz*Mz)) }}\n",
          name, light);
    }
    // Sphere: N = (P − C)/|P − C|, which holds for the shrunken copies too.
    const Vec3& c = obj.center;
    return fmt::format(
        "#declare {0}__1 = function(x, y, z, R) {{ {1}(x, y, z, (x-{2})/R, (y-{3})/R, (z-{4})/R) }}\n"
        "#declare {0} = function(x, y, z) {{ {0}__1(x, y, z, sqrt((x-{2})*(x-{2}) + (y-{3})*(y-{3}) + (z-{4})*(z-{4}))) }}\n",
        name, light, num(c.x), num(c.y), num(c.z));
  }

  // The interpolated normal of a mesh triangle as affine functions of the hit
  // point: m(P) = n0 + u(P)(n1 − n0) + v(P)(n2 − n0), with the barycentrics u, v
  // linear in P: u = (P − p0)·a1, v = (P − p0)·a2 for the dual basis a1, a2.
  static std::string triangle_normal(const Mesh& m, size_t t) {
    const auto& k = m.triangles[t];
    Vec3 p0 = m.positions[k[0]], e1 = m.positions[k[1]] - p0, e2 = m.positions[k[2]] - p0;
    Vec3 g = cross(e1, e2);
    double g2 = dot(g, g);
    if (g2 == 0) return fmt::format("{}, {}, {}", num(m.normals[k[0]].x), num(m.normals[k[0]].y), num(m.normals[k[0]].z));
    Vec3 a1 = cross(e2, g) / g2, a2 = cross(g, e1) / g2;
    Vec3 n0 = m.normals[k[0]], d1 = m.normals[k[1]] - n0, d2 = m.normals[k[2]] - n0;
    double c1 = dot(p0, a1), c2 = dot(p0, a2);
    std::string out;
    for (int j = 0; j < 3; ++j) {
      double cx = a1.x * d1[j] + a2.x * d2[j], cy = a1.y * d1[j] + a2.y * d2[j], cz = a1.z * d1[j] + a2.z * d2[j];
      double c0 = n0[j] - c1 * d1[j] - c2 * d2[j];
      out += fmt::format("{}{}*x + {}*y + {}*z + {}", j ? ", " : "", num(cx), num(cy), num(cz), num(c0));
    }
    return out;
  }

  // A pigment holding light i's radiance on object o (`call(ch)` evaluates it), × weight,
  // with transmit t. The function holds min(radiance·S, 1), S = the light's colour ×
  // exposure: exact up to the radiance at which the 16-bit output saturates anyway.
  std::string pigment(size_t o, size_t i, double weight, double t, const std::function<std::string(int)>& call) {
    const Shading& sh = *shadings_[shading_of_[o]];
    const RGB& c = s_.lights[i].color;
    std::string tr = t > 0 ? fmt::format(", {}", num(t)) : "";
    const char* kind = t > 0 ? "rgbt" : "rgb";
    if (!sh.dependent) {
      double smin = 0;
      for (double x : c)
        if (x > 0 && (smin == 0 || x < smin)) smin = x;
      if (smin == 0) return fmt::format("pigment {{ {} <0, 0, 0{}> }}", kind, tr);
      // The scale applies to the colour only: a vector times a number would scale
      // the transmit component too.
      std::string k = fmt::format("{}/({}*Facet_Exposure)", num(weight), num(smin));
      return fmt::format(
          "pigment {{ function {{ max(0, min(1, {0} * {1}*Facet_Exposure)) }}"
          " color_map {{ [0 {2} <0, 0, 0{3}>] [1 {2} <{4}, {4}, {4}{3}>] }} }}",
          call(0), num(smin), kind, tr, k);
    }
    std::string out = "pigment { average pigment_map {";
    for (int ch = 0; ch < 3; ++ch) {
      if (c[ch] == 0) {
        out += fmt::format(" [1 {} <0, 0, 0{}>]", kind, tr);
        continue;
      }
      std::string k = fmt::format("{}/({}*Facet_Exposure)", num(3 * weight), num(c[ch]));
      std::string e[3] = {"0", "0", "0"};
      e[ch] = k;
      out += fmt::format(
          "\n      [1 function {{ max(0, min(1, {0} * {1}*Facet_Exposure)) }}"
          " color_map {{ [0 {2} <0, 0, 0{3}>] [1 {2} <{4}, {5}, {6}{3}>] }}]",
          call(ch), num(c[ch]), kind, tr, e[0], e[1], e[2]);
    }
    return out + " } }";
  }

  static std::string lit_finish() { return "finish { ambient 0 emission 0 diffuse 1 brilliance 0 specular 0 phong 0 }"; }

  // Object o lit by light i, × weight, with transmit t.
  std::string lit(size_t o, size_t i, double weight, double t, double shrink, const std::string& mods) {
    const Object& obj = s_.objects[o];
    const Shading& sh = *shadings_[shading_of_[o]];
    if (obj.type != Object::Type::Mesh) {
      std::string tex = fmt::format("\n  texture {{ {} {} }}\n", pigment(o, i, weight, t, [&](int ch) {
        return fmt::format("Facet_Object{}_Light{}{}(x, y, z)", o, i, sh.suffix(ch));
      }), lit_finish());
      return object(o, shrink, tex, mods);
    }
    // One texture per triangle, from a macro taking the triangle's normal
    // functions (declared once, Facet_Object{o}_T{t}_X/Y/Z).
    const Mesh& m = *obj.mesh;
    std::string macro = fmt::format("Facet_Object{}_Light{}_Texture{}", o, i, weight == 1 && t == 0 ? "" : fmt::format("_{}", int(weight)));
    std::string out = fmt::format("#macro {}(NX, NY, NZ)\n  texture {{ {} {} }}\n#end\n", macro,
                                  pigment(o, i, weight, t, [&](int ch) {
                                    return fmt::format("Facet_Object{}_Light{}{}(x, y, z, NX(x, y, z), NY(x, y, z), NZ(x, y, z))",
                                                       o, i, sh.suffix(ch));
                                  }),
                                  lit_finish());
    std::string list = fmt::format("  texture_list {{ {}", m.triangles.size());
    for (size_t tr = 0; tr < m.triangles.size(); ++tr)
      list += fmt::format("{0}{1}(Facet_Object{2}_T{3}_X, Facet_Object{2}_T{3}_Y, Facet_Object{2}_T{3}_Z)",
                          tr % 2 == 0 ? ",\n    " : ", ", macro, o, tr);
    return out + object(o, shrink, list + "\n  }\n", mods);
  }

  // The interpolated normal of each triangle of mesh o, as three functions of the hit point.
  std::string mesh_normals(size_t o) {
    const Mesh& m = *s_.objects[o].mesh;
    std::string out = fmt::format("// Mesh \"{}\": each triangle's interpolated normal (unnormalized) at the hit point\n",
                                  s_.objects[o].name);
    for (size_t tr = 0; tr < m.triangles.size(); ++tr) {
      std::string n = triangle_normal(m, tr);
      size_t a = n.find(", "), b = n.find(", ", a + 2);
      // triangle_normal returns "X, Y, Z" with each a linear form in x, y, z.
      std::string comps[3] = {n.substr(0, a), n.substr(a + 2, b - a - 2), n.substr(b + 2)};
      for (int j = 0; j < 3; ++j)
        out += fmt::format("#declare Facet_Object{}_T{}_{} = function(x, y, z) {{ {} }}\n", o, tr, "XYZ"[j], comps[j]);
    }
    return out;
  }

  std::string emitting(size_t o, double weight, double t, double shrink, const std::string& mods) {
    const Shading& sh = *shadings_[shading_of_[o]];
    RGB e = sh.emission(s_);
    if (s_.objects[o].type != Object::Type::Mesh) return object(o, shrink, "\n  " + emission_texture(e, weight, t) + "\n", mods);
    const Mesh& m = *s_.objects[o].mesh;
    std::string list = fmt::format("  texture_list {{ {}", m.triangles.size());
    for (size_t tr = 0; tr < m.triangles.size(); ++tr) list += ",\n    " + emission_texture(e, weight, t);
    return object(o, shrink, list + "\n  }\n", mods);
  }

  std::string lit_objects() {
    std::string out = "// ---- Lights: the radiance of each light of unit colour, per material and object\n";
    for (const auto& sh : shadings_)
      for (size_t i = 0; i < s_.lights.size(); ++i)
        for (int ch = 0; ch < sh->channels(); ++ch) out += light_function(*sh, i, ch);
    for (size_t o = 0; o < s_.objects.size(); ++o)
      for (size_t i = 0; i < s_.lights.size(); ++i)
        for (int ch = 0; ch < shadings_[shading_of_[o]]->channels(); ++ch) out += object_function(o, i, ch);
    for (size_t o = 0; o < s_.objects.size(); ++o)
      if (s_.objects[o].type == Object::Type::Mesh) out += mesh_normals(o);
    out += "\n";
    size_t n = s_.lights.size();
    bool emits = false;
    for (size_t o = 0; o < s_.objects.size(); ++o) emits |= !black(shadings_[shading_of_[o]]->emission(s_));

    // One pass at a time is exact: Facet_Light = i < n renders light i alone,
    // i = n the emission (m_a ⊗ A + m_e) alone; the passes sum to the image.
    size_t items = n + (emits ? 1 : 0);
    auto pass = [&](size_t i) {
      std::string p = i < n ? light_source(s_.lights[i]) + "\n" : "";
      for (size_t o = 0; o < s_.objects.size(); ++o)
        p += (i < n ? lit(o, i, 1, 0, 0, "") : emitting(o, 1, 0, 0, "")) + "\n";
      return p;
    };
    if (items <= 1) return out + (items == 1 ? pass(0) : "");

    out += "#if (Facet_Light >= 0)\n#switch (Facet_Light)\n";
    for (size_t i = 0; i < items; ++i)
      out += fmt::format("#case ({})  // {}\n", i, i < n ? fmt::format("light {}", i) : "emission") + pass(i) + "#break\n";
    out += "#end\n#else\n";
    // Every pass at once: nested copies, one light_group each. Copy k lets
    // t_k = (items − k − 1)/(items − k) through to the copies inside it and keeps
    // 1 − t_k of its own pigment, so copy k is seen with weight
    // t_0 ⋯ t_(k−1) (1 − t_k) = 1/items: every pigment is scaled by items.
    for (size_t k = 0; k < items; ++k) {
      double t = double(items - 1 - k) / double(items - k);
      double weight = double(items);
      double shrink = 1e-4 * double(k);
      std::string mods = k + 1 == items ? "" : "  no_shadow\n";
      if (k < n) {
        out += "light_group {\n  " + light_source(s_.lights[k]) + "\n";
        for (size_t o = 0; o < s_.objects.size(); ++o) out += lit(o, k, weight, t, shrink, mods) + "\n";
        out += "  global_lights off\n}\n";
      } else {
        for (size_t o = 0; o < s_.objects.size(); ++o) out += emitting(o, weight, t, shrink, mods) + "\n";
      }
    }
    out += "#end\n";
    return out;
  }

  const Scene& s_;
  std::string source_;
  PovPlan plan_;
  std::vector<std::unique_ptr<Shading>> shadings_;
  std::vector<size_t> shading_of_;
  double scale_ = 1;
};

}  // namespace

std::string generate_pov(const Material& m, const GenerateOptions& o) {
  Scene s = o.scene ? *o.scene : default_scene();
  PovScene scene(s, &m, o.source);
  return o.library ? scene.library() : scene.render();
}

std::string generate_pov_sweep(const Material& m) {
  Scene s = default_scene();
  return PovScene(s, &m, m.source).sweep();
}

std::string generate_pov_scene(const Scene& s, const Material* fallback, const std::string& source) {
  PovScene scene(s, fallback, source);
  return scene.render();
}

}  // namespace facet
