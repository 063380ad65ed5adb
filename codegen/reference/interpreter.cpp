#include "reference/interpreter.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "catalog/texture.h"

namespace facet {

using ir::Op;

// ---------------------------------------------------------------- interpreter

// Each Function is flattened once into an array of nodes whose operands are
// indices, with parameters and lets resolved to frame slots.
struct Interpreter::Impl {
  struct CNode {
    Op op;
    int slot = -1;    // Arg, Local
    RGB value{};      // Literal, Constant
    int callee = -1;  // Call
    std::vector<int> args;
  };
  // A function's parameters and let-bindings, each a slot of its frame on the stack: glTF's
  // sheen with a roughness from an image binds about a hundred (catalog/specular.cpp,
  // sheen_per_pixel).
  static constexpr int kFrameSlots = 256;

  struct CFunction {
    std::vector<CNode> nodes;
    std::vector<std::pair<int, int>> lets;  // (slot, root)
    int result = -1;
    int slots = 0;
    int params = 0;
  };

  std::vector<CFunction> functions;
  std::unordered_map<const ir::Function*, int> index;

  int compile(const ir::Function& f) {
    if (auto it = index.find(&f); it != index.end()) return it->second;
    CFunction cf;
    std::unordered_map<std::string, int> slots;
    for (const auto& p : f.params) slots[p.name] = cf.slots++;
    cf.params = cf.slots;
    std::function<int(const ir::NodePtr&)> flatten = [&](const ir::NodePtr& n) -> int {
      CNode c;
      c.op = n->op;
      c.value = n->value;
      if (n->op == Op::Arg || n->op == Op::Local) c.slot = slots.at(n->name);
      if (n->op == Op::Call) c.callee = compile(*n->callee);
      for (const auto& a : n->args) c.args.push_back(flatten(a));
      cf.nodes.push_back(c);
      return int(cf.nodes.size() - 1);
    };
    for (const auto& l : f.lets) {
      int root = flatten(l.value.node());
      slots[l.name] = cf.slots++;
      cf.lets.emplace_back(slots[l.name], root);
    }
    cf.result = flatten(f.result.node());
    if (cf.slots > kFrameSlots)
      throw std::logic_error("facet reference: " + f.name + " has " + std::to_string(cf.slots) + " slots, more than " +
                             std::to_string(kFrameSlots));
    functions.push_back(std::move(cf));
    int id = int(functions.size() - 1);
    index[&f] = id;
    return id;
  }

  RGB run(int fid, const RGB* args) const {
    const CFunction& f = functions[fid];
    RGB frame[kFrameSlots];
    for (int i = 0; i < f.params; ++i) frame[i] = args[i];
    for (const auto& [slot, root] : f.lets) frame[slot] = eval(f, root, frame);
    return eval(f, f.result, frame);
  }

  static RGB lanes(const RGB& a, double (*fn)(double)) { return {fn(a[0]), fn(a[1]), fn(a[2])}; }
  template <class F>
  static RGB lanes2(const RGB& a, const RGB& b, F fn) {
    return {fn(a[0], b[0]), fn(a[1], b[1]), fn(a[2], b[2])};
  }

  // Conditions are floats (lane 0); only the chosen side of a select is evaluated.
  bool test(const CFunction& f, int i, const RGB* frame) const {
    const CNode& n = f.nodes[i];
    switch (n.op) {
      case Op::And: return test(f, n.args[0], frame) && test(f, n.args[1], frame);
      case Op::Or: return test(f, n.args[0], frame) || test(f, n.args[1], frame);
      default: break;
    }
    double a = eval(f, n.args[0], frame)[0], b = eval(f, n.args[1], frame)[0];
    switch (n.op) {
      case Op::Lt: return a < b;
      case Op::Le: return a <= b;
      case Op::Gt: return a > b;
      case Op::Ge: return a >= b;
      default: throw std::logic_error("facet reference: not a condition");
    }
  }

  RGB eval(const CFunction& f, int i, const RGB* frame) const {
    const CNode& n = f.nodes[i];
    auto arg = [&](int k) { return eval(f, n.args[k], frame); };
    switch (n.op) {
      case Op::Literal:
      case Op::Constant: return n.value;
      case Op::Arg:
      case Op::Local: return frame[n.slot];
      case Op::Neg: return lanes(arg(0), [](double x) { return -x; });
      case Op::Add: return lanes2(arg(0), arg(1), [](double a, double b) { return a + b; });
      case Op::Sub: return lanes2(arg(0), arg(1), [](double a, double b) { return a - b; });
      case Op::Mul: return lanes2(arg(0), arg(1), [](double a, double b) { return a * b; });
      case Op::Div: return lanes2(arg(0), arg(1), [](double a, double b) { return a / b; });
      case Op::Min: return lanes2(arg(0), arg(1), [](double a, double b) { return std::fmin(a, b); });
      case Op::Max: return lanes2(arg(0), arg(1), [](double a, double b) { return std::fmax(a, b); });
      case Op::Clamp: {
        RGB x = arg(0), lo = arg(1), hi = arg(2);
        return {std::fmin(std::fmax(x[0], lo[0]), hi[0]), std::fmin(std::fmax(x[1], lo[1]), hi[1]),
                std::fmin(std::fmax(x[2], lo[2]), hi[2])};
      }
      case Op::Sqrt: return lanes(arg(0), [](double x) { return std::sqrt(x); });
      case Op::Exp: return lanes(arg(0), [](double x) { return std::exp(x); });
      case Op::Pow: return lanes2(arg(0), arg(1), [](double a, double b) { return std::pow(a, b); });
      case Op::Acos: return lanes(arg(0), [](double x) { return std::acos(x); });
      case Op::Atan2: return lanes2(arg(0), arg(1), [](double a, double b) { return std::atan2(a, b); });
      case Op::Abs: return lanes(arg(0), [](double x) { return std::fabs(x); });
      case Op::Sin: return lanes(arg(0), [](double x) { return std::sin(x); });
      case Op::Cos: return lanes(arg(0), [](double x) { return std::cos(x); });
      case Op::Floor: return lanes(arg(0), [](double x) { return std::floor(x); });
      case Op::Step: return lanes2(arg(0), arg(1), [](double e, double x) { return x >= e ? 1.0 : 0.0; });
      case Op::Select: return test(f, n.args[0], frame) ? arg(1) : arg(2);
      case Op::Call: {
        RGB args[kFrameSlots];
        for (size_t k = 0; k < n.args.size(); ++k) args[k] = eval(f, n.args[k], frame);
        return run(n.callee, args);
      }
      case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::And: case Op::Or:
        throw std::logic_error("facet reference: a condition used as a value");
    }
    throw std::logic_error("facet reference: unknown op");
  }
};

Interpreter::Interpreter() : impl_(std::make_unique<Impl>()) {}
Interpreter::~Interpreter() = default;
Interpreter::Interpreter(Interpreter&&) noexcept = default;
Interpreter& Interpreter::operator=(Interpreter&&) noexcept = default;

int Interpreter::prepare(const ir::FunctionPtr& f) { return impl_->compile(*f); }

RGB Interpreter::run(int prepared, const RGB* args) const { return impl_->run(prepared, args); }

RGB Interpreter::call(const ir::FunctionPtr& f, const std::vector<RGB>& args) {
  if (args.size() != f->params.size()) throw std::logic_error("facet reference: wrong argument count for " + f->name);
  return run(prepare(f), args.data());
}

double Interpreter::call_float(const ir::FunctionPtr& f, const std::vector<double>& args) {
  std::vector<RGB> a;
  for (double x : args) a.push_back({x, x, x});
  return call(f, a)[0];
}

// ---------------------------------------------------------------- shading inputs

int ShadingInputs::index(const std::string& name) {
  const auto& order = input_order();
  for (size_t i = 0; i < order.size(); ++i)
    if (order[i] == name) return int(i);
  throw std::logic_error("facet reference: unknown shading input " + name);
}

namespace {
// Every shading input (catalog.h: Input, whose last is CoH), the size of an argument list.
constexpr size_t kInputCount = size_t(Input::CoH) + 1;
}

double ShadingInputs::get(int i) const {
  const double v[] = {NoL, NoV, LoV, LoT, VoT, LoB, VoB, NoH, VoH, HoT, HoB, CoL, CoV, CoH};
  static_assert(sizeof v / sizeof v[0] == kInputCount, "one value per Input");
  return v[i];
}

double ShadingInputs::get(const std::string& name) const { return get(index(name)); }

ShadingInputs shading_inputs(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t) {
  return shading_inputs(n, l, v, t, n);
}

ShadingInputs shading_inputs(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t, const Vec3& c, double w) {
  Vec3 b = cross(n, t) * w;
  ShadingInputs s;
  s.NoL = dot(n, l);
  s.NoV = dot(n, v);
  s.LoV = dot(l, v);
  s.LoT = dot(l, t);
  s.VoT = dot(v, t);
  s.LoB = dot(l, b);
  s.VoB = dot(v, b);
  // catalog.h, Input: the half vector, its length floored at ε.
  Vec3 h = (l + v) / std::max(length(l + v), kEpsilon);
  s.NoH = dot(n, h);
  s.VoH = dot(v, h);
  s.HoT = dot(h, t);
  s.HoB = dot(h, b);
  s.CoL = dot(c, l);
  s.CoV = dot(c, v);
  s.CoH = dot(c, h);
  return s;
}

Vec3 perturb_normal(const Vec3& n, const Vec3& t, double w, const std::array<double, 3>& nt) {
  const Vec3 T = normalize(t - n * dot(n, t));
  const Vec3 B = cross(n, T) * w;
  return normalize(T * nt[0] + B * nt[1] + n * nt[2]);
}

Vec3 follow_normal(const Vec3& t, const Vec3& mapped) { return normalize(t - mapped * dot(mapped, t)); }

// ---------------------------------------------------------------- Reference

Reference::Reference(const Material& m) : program_(compile(m)) {
  if (program_.textured.size() > kMaxTexturedInputs)
    throw std::logic_error(fmt::format("facet reference: {} textured parameters; at most {}", program_.textured.size(),
                                       kMaxTexturedInputs));
  // Each derived max₃'s colour (TexturedInput::max_of), sampled before it.
  const auto& textured = program_.textured;
  max_of_.assign(textured.size(), 0);
  for (size_t i = 0; i < textured.size(); ++i)
    if (!textured[i].max_of.empty())
      max_of_[i] = size_t(std::find_if(textured.begin(), textured.begin() + long(i),
                                       [&](const TexturedInput& x) { return x.name == textured[i].max_of; }) -
                          textured.begin());
  reflectance_ = prepare(program_.reflectance);
  if (program_.diffuse) diffuse_ = prepare(program_.diffuse);
  if (program_.specular) specular_ = prepare(program_.specular);
  inverse_square_ = interp_.prepare(terms::attenuation_inverse_square());
  polynomial_ = interp_.prepare(terms::attenuation_polynomial());
  windowed_ = interp_.prepare(terms::attenuation_inverse_square_range());
  spot_ = interp_.prepare(terms::spot_cone());
  if (program_.emission_weight) emission_weight_ = prepare(program_.emission_weight);
}

double Reference::light_factor(const Light& light, const Vec3& l, double d) const {
  if (light.type == Light::Type::Directional) return 1.0;
  auto f = [](double x) { return RGB{x, x, x}; };
  double factor = 1.0;
  const Attenuation& a = light.attenuation;
  if (a.law == Attenuation::Law::InverseSquare) {
    RGB args[] = {f(d)};
    factor = interp_.run(inverse_square_, args)[0];
  } else if (a.law == Attenuation::Law::Polynomial) {
    RGB args[] = {f(d), f(a.constant), f(a.linear), f(a.quadratic)};
    factor = interp_.run(polynomial_, args)[0];
  } else if (a.law == Attenuation::Law::InverseSquareRange) {
    RGB args[] = {f(d), f(a.range)};
    factor = interp_.run(windowed_, args)[0];
  }
  if (light.type == Light::Type::Spot) {
    RGB args[] = {f(-dot(l, light.direction)), f(std::cos(light.cutoff * M_PI / 180.0)), f(light.exponent)};
    factor *= interp_.run(spot_, args)[0];
  }
  return factor;
}

Reference::Prepared Reference::prepare(const ir::FunctionPtr& f) {
  Prepared p;
  p.id = interp_.prepare(f);
  if (f->params.size() > kInputCount + kMaxTexturedInputs)
    throw std::logic_error("facet reference: too many inputs for " + f->name);
  const auto& textured = program_.textured;
  for (const auto& param : f->params) {
    // A textured parameter's slot follows the dot products'.
    auto t = std::find_if(textured.begin(), textured.end(), [&](const TexturedInput& x) { return x.name == param.name; });
    p.inputs.push_back(t != textured.end() ? int(kInputCount + size_t(t - textured.begin()))
                                           : ShadingInputs::index(param.name));
  }
  return p;
}

RGB Reference::call(const Prepared& f, const ShadingInputs& in) const {
  RGB args[kInputCount + kMaxTexturedInputs];  // a function reads each input at most once
  for (size_t i = 0; i < f.inputs.size(); ++i) {
    const size_t k = size_t(f.inputs[i]);
    if (k >= kInputCount) {
      args[i] = in.textured[k - kInputCount];
    } else {
      double x = in.get(f.inputs[i]);
      args[i] = {x, x, x};
    }
  }
  return interp_.run(f.id, args);
}

bool Reference::sample_textures(const std::array<std::array<double, 2>, 2>& uv, ShadingInputs& in,
                                const VertexColor& color0) const {
  const auto& textured = program_.textured;
  bool fragile = false;
  for (size_t i = 0; i < textured.size(); ++i) {
    const TexturedInput& t = textured[i];
    if (!t.max_of.empty()) {  // max₃ of the colour sampled before it
      const RGB& c = in.textured[max_of_[i]];
      const double m = std::max({c[0], c[1], c[2]});
      in.textured[i] = {m, m, m};
      continue;
    }
    const auto& st = uv[size_t(t.value.texture->uv)];
    in.textured[i] = texture_value(t.value, t.range, st[0], st[1], &fragile, color0);
  }
  return fragile;
}

RGB Reference::emitted(const ShadingInputs& in, const RGB& scene_ambient, double NoV) const {
  const Material& m = program_.material;
  RGB ambient = m.ambient, emission = m.emission;
  const auto& textured = program_.textured;
  for (size_t i = 0; i < textured.size(); ++i) {
    if (textured[i].name == kAmbientInput) ambient = in.textured[i];
    if (textured[i].name == kEmissionInput) emission = in.textured[i];
  }
  double weight = 1;
  if (program_.emission_weight) {  // NoV, then the textured parameters it reads, sampled into `in`
    ShadingInputs at = in;
    at.NoV = NoV;
    weight = call(emission_weight_, at)[0];
  }
  RGB L;
  for (size_t c = 0; c < 3; ++c) L[c] = ambient[c] * scene_ambient[c] + emission[c] * weight;
  return L;
}

Vec3 Reference::mapped_normal(const std::array<std::array<double, 2>, 2>& uv, const Vec3& n, const Vec3& t, double w,
                              bool& fragile, bool coat) const {
  const NormalMap& m = coat ? *material().coat_normal_map : *material().normal_map;
  const auto& st = uv[size_t(m.texture().uv)];
  const auto rgb = normal_map_rgb(m, st[0], st[1], &fragile);
  return perturb_normal(n, t, w, normal_map_tangent_normal(m, rgb));
}

RGB Reference::reflectance(const ShadingInputs& in) const { return call(reflectance_, in); }

RGB Reference::reflectance(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t) const {
  return reflectance(shading_inputs(n, l, v, t));
}

RGB Reference::reflectance(const Vec3& n, const Vec3& l, const Vec3& v) const {
  return reflectance(n, l, v, tangent_rule(n, Vec3(material().tangent_axis)));
}

RGB Reference::rho_diffuse(const ShadingInputs& in) const {
  return program_.diffuse ? call(diffuse_, in) : RGB{0, 0, 0};
}

RGB Reference::rho_specular(const ShadingInputs& in) const {
  return program_.specular ? call(specular_, in) : RGB{0, 0, 0};
}

}  // namespace facet
