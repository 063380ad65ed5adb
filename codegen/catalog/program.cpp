#include "catalog/program.h"

#include <algorithm>

#include <fmt/format.h>

#include "catalog/texture.h"
#include "core/diagnostics.h"

namespace facet {

std::string describe(const ModelSpec& s) {
  std::string d = s.def->title;
  std::string params;
  for (const auto& p : s.def->params) {
    if (p.kind != ParamKind::Number) continue;
    const Value& v = s.at(p.name);
    if (v.texture && v.texture->has_image())
      params += fmt::format("{}{} from \"{}\"{}", params.empty() ? "" : ", ", p.name, v.texture->file,
                            v.texture->vertex_color ? " and the vertex colour" : "");
    else if (v.texture)
      params += fmt::format("{}{} from the vertex colour", params.empty() ? "" : ", ", p.name);
    else
      params += fmt::format("{}{} = {}", params.empty() ? "" : ", ", p.name, v.number);
  }
  return params.empty() ? d : d + " (" + params + ")";
}

namespace {

// rho_<lobe>(inputs…): the model's formula, then the toon modifier.
ir::FunctionPtr build_lobe(const ModelSpec& spec, const std::string& lobe, const Material& material,
                           std::vector<TexturedInput>& textured) {
  ir::FunctionBuilder fb("rho_" + lobe, fmt::format("The {} lobe of \"{}\": {}", lobe, material.name, describe(spec)));
  LobeContext ctx(spec, lobe, fb, material.coat_normal_differs());
  ir::Expr rho = lobe_rho(ctx);
  fb.order_params(input_order());
  for (const auto& t : ctx.textured_inputs()) textured.push_back(t);
  return fb.returns(rho);
}

std::vector<ir::Expr> args_for(const ir::FunctionPtr& f, const ir::FunctionBuilder& fb) {
  std::vector<ir::Expr> args;
  for (const auto& p : f->params) args.push_back(fb.arg(p.name));
  return args;
}

// The name the i-th layer's values and function take ("layer0"), and its key in the material.
std::string layer_name(size_t i) { return "layer" + std::to_string(i); }

// layer<i>_<model>(base, inputs…): the layer's ρ over `base`, ρ of everything under it
// (ModelDef::layer).
ir::FunctionPtr build_layer(const Material& material, size_t i, std::vector<TexturedInput>& textured) {
  const ModelSpec& spec = material.layers[i];
  const std::string name = layer_name(i);
  ir::FunctionBuilder fb(name + "_" + spec.def->name,
                         fmt::format("Layer {} of \"{}\" over what lies under it: {} — {}", i, material.name,
                                     describe(spec), spec.def->citation));
  ir::Expr base = fb.param("base", ir::Type::Color);
  LobeContext ctx(spec, name, fb, material.coat_normal_differs(), fmt::format("layers[{}]", i));
  ir::Expr rho = spec.def->layer(ctx, base);
  if (rho.type() != ir::Type::Color) rho = rho * ir::color(1, 1, 1);
  std::vector<std::string> order = {"base"};
  order.insert(order.end(), input_order().begin(), input_order().end());
  fb.order_params(order);
  for (const auto& t : ctx.textured_inputs()) textured.push_back(t);
  return fb.returns(rho);
}

// m_e's weight under the layers over it: the specular lobe's, then each layer's (ModelDef::
// emission_weight), their product where there are several (each then in `each`); null where
// nothing lies over it.
ir::FunctionPtr emission_weight(const Material& m, std::vector<ir::FunctionPtr>& each) {
  struct Over {
    const ModelSpec* spec;
    std::string lobe;
  };
  std::vector<Over> over;
  if (m.specular && m.specular->def->emission_weight) over.push_back({&*m.specular, "specular"});
  for (size_t i = 0; i < m.layers.size(); ++i)
    if (m.layers[i].def->emission_weight) over.push_back({&m.layers[i], layer_name(i)});
  std::vector<ir::FunctionPtr> weights;
  for (const auto& o : over)
    if (auto w = o.spec->def->emission_weight(*o.spec, o.lobe, "emission_weight_" + o.lobe)) weights.push_back(w);
  if (weights.empty()) return nullptr;
  if (weights.size() == 1)  // one layer: its own function, under the name every target calls
    for (const auto& o : over)
      if (auto w = o.spec->def->emission_weight(*o.spec, o.lobe, "emission_weight")) return w;
  each = weights;
  ir::FunctionBuilder fb("emission_weight", "the emission under every layer over it: the product of their weights");
  fb.param("NoV");
  for (const auto& w : weights)
    for (const auto& param : w->params) fb.param(param.name, param.type);
  ir::Expr product = 1.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    ir::Expr call = ir::call(weights[i], args_for(weights[i], fb));
    product = i == 0 ? call : product * call;
  }
  return fb.returns(product);
}

}  // namespace

bool MaterialProgram::is_textured(const std::string& input) const {
  return std::any_of(textured.begin(), textured.end(), [&](const TexturedInput& t) { return t.name == input; });
}

bool MaterialProgram::uses_vertex_color() const {
  return std::any_of(textured.begin(), textured.end(), [](const TexturedInput& t) { return t.value.texture->vertex_color; });
}

bool MaterialProgram::uses(const std::string& input) const {
  return std::find(inputs.begin(), inputs.end(), input) != inputs.end();
}

std::vector<ir::FunctionPtr> MaterialProgram::functions() const {
  std::vector<ir::FunctionPtr> roots = {terms::attenuation_inverse_square(), terms::attenuation_polynomial(),
                                        terms::attenuation_inverse_square_range(), terms::spot_cone(), reflectance};
  if (emission_weight) roots.push_back(emission_weight);
  return ir::dependencies(roots);
}

std::vector<ir::NodePtr> MaterialProgram::constants() const {
  return emission_weight ? ir::constants({reflectance, emission_weight}) : ir::constants({reflectance});
}

MaterialProgram compile(const Material& m) {
  MaterialProgram p;
  p.material = m;
  if (m.diffuse) p.diffuse = build_lobe(*m.diffuse, "diffuse", m, p.textured);
  if (m.specular) p.specular = build_lobe(*m.specular, "specular", m, p.textured);

  for (size_t i = 0; i < m.layers.size(); ++i) p.layers.push_back(build_layer(m, i, p.textured));

  ir::FunctionBuilder fb("reflectance",
                         m.layers.empty() ? "MODELS.md: k_d ⊗ ρ_d(l, v) + k_s ⊗ ρ_s(l, v) for a light of unit colour"
                                          : "MODELS.md: k_d ⊗ ρ_d(l, v) + k_s ⊗ ρ_s(l, v) under the material's layers, "
                                            "for a light of unit colour",
                         "Horizon rule: nothing is reflected where n·l ≤ 0 or n·v ≤ 0, i.e. min(n·l, n·v) ≤ 0.");
  // n·l and n·v always, for the horizon rule; then whatever the lobes and layers read.
  fb.param("NoL");
  fb.param("NoV");
  std::vector<ir::FunctionPtr> parts = {p.diffuse, p.specular};
  parts.insert(parts.end(), p.layers.begin(), p.layers.end());
  for (const auto& part : parts)
    if (part)
      for (const auto& param : part->params)
        if (param.name != "base") fb.param(param.name, param.type);

  ir::Expr sum = 0.0;
  bool first = true;
  auto add = [&](const ir::FunctionPtr& lobe, const ModelSpec& spec, const char* name) {
    const Value& color = spec.at("color");
    const std::string k_name = std::string(name) + "_color";
    ir::Expr k = ir::constant(k_name, color.rgb);
    if (color.texture) {
      k = fb.param(k_name, ir::Type::Color);
      p.textured.push_back({k_name, std::string(name) + ".color", ir::Type::Color, color, spec.def->param("color")->range, ""});
    }
    ir::Expr term = k * ir::call(lobe, args_for(lobe, fb));
    sum = first ? term : sum + term;
    first = false;
  };
  if (p.diffuse) add(p.diffuse, *m.diffuse, "diffuse");
  if (p.specular) add(p.specular, *m.specular, "specular");
  // Each layer over what lies under it, the first lowest.
  if (!p.layers.empty() && sum.type() != ir::Type::Color) sum = sum * ir::color(1, 1, 1);
  for (const auto& layer : p.layers) {
    std::vector<ir::Expr> args = {sum};
    for (size_t i = 1; i < layer->params.size(); ++i) args.push_back(fb.arg(layer->params[i].name));
    sum = ir::call(layer, args);
  }
  fb.order_params(input_order());
  ir::Expr horizon_zero = ir::color(0, 0, 0);
  // One comparison of the smaller cosine rather than two and an ||: the same test.
  p.reflectance = fb.returns(ir::select(ir::min(fb.arg("NoL"), fb.arg("NoV")) <= 0.0, horizon_zero, sum));
  for (const auto& param : p.reflectance->params) p.inputs.push_back(param.name);
  // m_a and m_e from images: sampled like the lobes' parameters, read by the shading
  // itself (m_a ⊗ A + m_e), not by the reflectance.
  for (bool ambient : {true, false}) {
    Value v = material_term(m, ambient);
    if (v.texture)
      p.textured.push_back({ambient ? kAmbientInput : kEmissionInput, ambient ? "ambient" : "emission", ir::Type::Color,
                            v, Range::color(), ""});
  }
  const bool emits = m.emission_texture || m.emission != RGB{0, 0, 0};
  if (emits) p.emission_weight = emission_weight(m, p.emission_weights);
  return p;
}

void require_no_images(const Material& m, const std::string& why) {
  const MaterialProgram p = compile(m);
  // A frame the lobes' tangent alone reads is given as t (w = +1) where nothing samples images.
  if (p.textured.empty() && !m.normal_map && !m.coat_normal_map) return;
  const std::string file = m.source.empty() ? m.name : m.source;
  std::vector<Diagnostic> d;
  for (const auto& t : p.textured)
    if (t.max_of.empty()) d.push_back({file, t.key, "an image texture, " + why});  // a derived max₃ names no key
  if (m.normal_map) d.push_back({file, "normal_map", "a normal map, " + why});
  if (m.coat_normal_map) d.push_back({file, "coat_normal_map", "a normal map, " + why});
  throw InputError(d);
}

ir::FunctionPtr lobe_reflectance(const MaterialProgram& p, bool specular) {
  const ir::FunctionPtr& lobe = specular ? p.specular : p.diffuse;
  if (!lobe) return nullptr;
  const std::string which = specular ? "specular" : "diffuse";
  ir::FunctionBuilder fb("reflectance_" + which,
                         fmt::format("MODELS.md: ρ_{}(l, v), the {} lobe without its colour", which[0], which),
                         "Horizon rule: nothing is reflected where n·l ≤ 0 or n·v ≤ 0, i.e. min(n·l, n·v) ≤ 0.");
  // n·l and n·v for the horizon rule, then what the lobe reads.
  fb.param("NoL");
  fb.param("NoV");
  for (const auto& param : lobe->params) fb.param(param.name, param.type);
  fb.order_params(input_order());
  ir::Expr zero = lobe->result_type() == ir::Type::Color ? ir::color(0, 0, 0) : ir::Expr(0.0);
  return fb.returns(ir::select(ir::min(fb.arg("NoL"), fb.arg("NoV")) <= 0.0, zero, ir::call(lobe, args_for(lobe, fb))));
}

}  // namespace facet
