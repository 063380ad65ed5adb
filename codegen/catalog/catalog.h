// facet — the model catalog.
//
// Every reflection model, Fresnel term, geometry term, modifier, light and
// attenuation law of MODELS.md is one `ModelDef`: its parameters (type, range,
// default, documentation), its citation, its formula as documentation, how
// exactly Cycles and POV-Ray can express it natively, what the scene layer reads
// of it (the kind of an object, light or attenuation law; a lobe's glTF
// equivalent), and — for the lobes — the function that builds its formula in the
// IR. Printers and the C++ reference only ever see that IR, so adding a model
// means adding one ModelDef.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/ir.h"

namespace facet {

// ε of MODELS.md: the one tolerance every target uses (see catalog/README in the docs).
inline constexpr double kEpsilon = 1e-4;

// ---- What float32 targets can hold (docs/float32.md derives each bound from the
// formulas): every number a material or scene file carries into GLSL, OSL or
// POV-Ray code is bounded so that every target evaluates it without overflow.
// Colours: k_d, k_s, m_a, m_e, a light's C, the scene's A (and texture factors).
// With every factor of L = m_a A + Σ att spot C (k_d ρ_d + k_s ρ_s) + m_e at most
// 1e4 and each ρ below 1e15 (n·v ≥ 1e-7), L stays below 1e24 a light: 14 orders
// of magnitude inside float32's 3.4e38.
inline constexpr double kColorMax = 1e4;
// A light's colour C: real light powers in physical units reach beyond 1e4 (a 1 MW
// Blender light is C = 1e6 / (4π²) ≈ 2.5e4; glTF's candela and lux convert to C by
// 1 / (683 lm/W · π)), so lights take 1e6: a light then adds at most 1e6 · 2.5e16 = 2.5e22
// (docs/float32.md), still 16 orders of magnitude inside float32.
inline constexpr double kLightColorMax = 1e6;
// Exponents x^n of a cosine (phong, blinn_phong, heidrich_seidel n, minnaert k, a
// spot's exponent; gaussian m): every such cosine is clamped into [0, 1]
// (ir::unit), so x^n ≤ 1 and Schlick's x / (n − n x + x) keeps a denominator ≥ 1;
// the number itself must stay finite in float code (an ∞ n makes n − n x NaN).
inline constexpr double kExponentMax = 1e6;
// Roughness (m, α, α_x, α_y): the smallest non-zero tan²θ_h a float32 half vector
// reaches is 2^-23 ≈ 1.2e-7, and exp(−1.2e-7 / m²) underflows (below e^-87.3) for
// m < 3.7e-5: there the lobe is one half vector, only its peak 1/(π m²) grows. The
// bound is 1e-3, where a textured roughness was already clamped (kTextureOpenMargin),
// so that a constant and an image share it; the peak is then at most 3.2e5.
inline constexpr double kRoughnessMin = 1e-3;
// Every other unbounded number (σ, roughness, η, toon's cutoff and width, the
// attenuation coefficients): beyond 1e4 its squares stay below 1e8 and the
// formulas have reached their limits to float32 precision (σ²/(σ² + 0.57) rounds
// to 1 beyond σ ≈ 3.1e3).
inline constexpr double kScalarMax = 1e4;
// Scene coordinates (positions, look_at, centres, mesh vertices, texture coordinates,
// a sphere's radius, a square's size; directions too, which C++ normalizes): with
// |x| ≤ 1e6 the ray caster's |o − c|², b² − 4ac and d² stay below 1e26, and a point
// light's c₃ d² below 1e17.
inline constexpr double kCoordinateMax = 1e6;

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
  // A bound set for float32 (the helpers below), not by the model: analyses that step
  // over a model's own range (facet physics) step around the default instead.
  bool float32 = false;
  bool contains(double v) const;
  std::string describe() const;  // "> 0", "in [0, 1]", "any"
  static Range positive() { return {0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range at_least(double v) { return {v, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range left_open(double a, double b) { return {a, b, true, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  // The float32 bounds above as ranges.
  static Range color() { return {0, kColorMax, false, false, true}; }                    // [0, 1e4]
  static Range light_color() { return {0, kLightColorMax, false, false, true}; }         // [0, 1e6]
  static Range exponent(double lo) { return {lo, kExponentMax, false, false, true}; }       // [lo, 1e6]
  static Range positive_exponent() { return {0, kExponentMax, true, false, true}; }         // (0, 1e6]
  static Range roughness() { return {kRoughnessMin, kScalarMax, false, false, true}; }      // [1e-3, 1e4]
  static Range scalar() { return {0, kScalarMax, false, false, true}; }                     // [0, 1e4]
  static Range positive_scalar() { return {0, kScalarMax, true, false, true}; }             // (0, 1e4]
  static Range coordinate() { return {-kCoordinateMax, kCoordinateMax, false, false, true}; }  // [-1e6, 1e6]
  static Range positive_coordinate() { return {0, kCoordinateMax, true, false, true}; }     // (0, 1e6]
};

// The shortest vector that is a direction: one component at least this in size (a shorter
// one's length squared underflows in float32, where the targets normalize; docs/float32.md).
constexpr double kShortestDirection = 1e-6;

enum class ParamKind {
  Number,  // a finite JSON number within `range`
  Bool,
  Enum,    // one of `choices`
  Color,   // an RGB array, or one number for grey; components within `range`
  Vector,  // three numbers (a direction if `nonzero`: some component at least kShortestDirection in size)
  Model,   // an object {"model": <a name of section `section`>, …its parameters}
  Object,  // an object holding the parameters of the fixed model `section`/`fixed`
  String,     // a non-empty string
  Points,     // an array of [x, y, z] (mesh positions and normals)
  Triangles,  // an array of [a, b, c] vertex indices
  Index,      // an index (a whole number ≥ 0), or with `by_name` also a name (a non-empty string)
};
const char* param_kind_name(ParamKind k);

// A parameter's value in a material (after defaults are applied).
struct ModelSpec;
struct TextureRef;  // catalog/texture.h
struct Value {
  ParamKind kind = ParamKind::Number;
  double number = 0;
  bool flag = false;
  std::string choice;
  std::array<double, 3> rgb{};
  std::shared_ptr<const ModelSpec> model;  // Model and Object kinds
  // Points and Triangles kinds: the first ParamDef::arity numbers of each element hold the values.
  std::vector<std::array<double, 4>> points;
  int arity = 3;  // Points: numbers an element
  // Number and Color kinds (ParamDef::texturable): the value comes from an image, times
  // the factor `number` / `rgb` holds, clamped to the range (catalog/texture.h).
  std::shared_ptr<const TextureRef> texture;
  // Index kind: `number` holds the index, or −1 where `choice` holds a name (or the key is absent).
};

struct ParamDef {
  std::string name;
  ParamKind kind = ParamKind::Number;
  std::string doc;
  Range range;
  bool required = false;
  Value fallback;                    // the value when the key is absent (optional parameters),
                                     // or the value editors start from (required ones)
  std::vector<std::string> choices;  // Enum
  std::string section;               // Model: the section to choose from; Object: the model's section
  std::string fixed;                 // Object: the model whose parameters the object holds;
                                     // Model: the model an object without "model" means
  bool nonzero = false;              // Vector: a direction, so no shorter than kShortestDirection
  bool every_lobe = false;           // one of the parameters every diffuse and specular lobe takes (color, toon)
  bool by_name = false;              // Index: a name is allowed as well as an index
  bool texturable = false;           // Number, Color: may come from an image ({"texture": …})
  int arity = 3;                     // Points: numbers an element (2: texture coordinates [u, v]; 4: tangents [x, y, z, w])
  std::string allowed() const;       // what the error messages say is allowed
};

// How closely a renderer's own feature reproduces a model.
struct Equivalence {
  enum class Level { Exact, Approximate, None };
  Level level = Level::None;
  std::string note;
};
const char* level_name(Equivalence::Level l);

// Blender's own shader nodes nearest a lobe model: what the add-on's "Build Blender
// Nodes" makes (exporters/blender/facet_blender/core/native.py) and how close it comes,
// MEASURED: the worst |Δ|/max(1, |ref|) of a Cycles render (one point light of radius 0,
// direct light only) against facet's reference, the worst over the lobes of this model in
// examples/materials/*.json, each built alone. exporters/blender/tests/run_tests.py
// (test_native_nodes_match_published_error) measures it again: exact within 2e-3,
// approximate within 10 % of `error`. Level None: no node stands in (`nodes` says why).
struct BlenderNodes {
  Equivalence::Level level = Equivalence::Level::None;
  std::string nodes;   // the node(s) and how the model's parameters map onto them
  double error = 0.0;  // approximate: the measured worst |Δ|/max(1, |ref|)
};

// ---- POV-Ray's native finish (read by targets/pov.cpp) -----------------------
// Where POV-Ray's own finish is a lobe exactly (shared/notes/povray.md §2): the
// finish keywords it sets, where each value comes from, and what the material
// must hold for it. A lobe without terms is evaluated in function pigments.
struct PovFinishTerm {
  enum class From {
    Weight,      // the lobe's weight in the texture: 1, or 2 under an emission layer
    GreyColor,   // the colour parameter `param` (grey: POV-Ray's highlights are white) × the weight
    Number,      // the number parameter `param`
    Reciprocal,  // 1 / the number parameter `param`
    Fixed,       // `value`
  };
  std::string keyword;  // e.g. "phong_size"
  From from = From::Fixed;
  std::string param;
  double value = 0;
};
struct PovFinishRequirement {
  enum class Kind {
    Choice,  // the Enum parameter `param` holds `choice`
    Absent,  // the Object parameter `param` is absent (toon)
    Grey,    // the Color parameter `param` is grey
  };
  Kind kind = Kind::Choice;
  std::string param;
  std::string choice;
  std::string why;  // why the lobe is no finish where the requirement fails
};
struct PovFinish {
  std::vector<PovFinishTerm> terms;  // in the order printed; empty: not a finish
  std::string pigment;               // the Color parameter that is the pigment (diffuse: "color", k_d), or ""
  std::vector<PovFinishRequirement> requirements;  // checked in order
  bool native() const { return !terms.empty(); }
};
// ---- end of POV-Ray's native finish

class LobeContext;

// One way of writing an object whose parameters come in alternatives (a mesh: its
// arrays inline, or a reference to a glTF file). `keys` are the parameters the form
// needs, `optional` those it also allows; a parameter of another form is an error.
struct ParamForm {
  std::string what;  // "inline arrays", "a glTF file's node"
  std::vector<std::string> keys;
  std::vector<std::string> optional;
};

// The scene vocabulary's kinds, as the catalog states them: the scene layer builds
// an object, a light or an attenuation law from the kind its model has (scene.h's
// Object::Type, Light::Type and Attenuation::Law are these enums), never from the
// model's name.
enum class ObjectType { Sphere, Plane, Mesh };
enum class LightType { Point, Directional, Spot };
enum class AttenuationLaw { None, InverseSquare, Polynomial, InverseSquareRange };

struct ModelDef {
  std::string section;   // diffuse, specular, layer, fresnel, geometry, distribution, modifier, light, attenuation, term
  std::string name;      // the key used in material files
  std::string title;     // human name
  std::string citation;  // printed on the first line of the generated function
  std::string formula;   // the formula as in MODELS.md
  std::string doc;       // a paragraph for `facet models` and the docs
  std::vector<ParamDef> params;
  // Empty: any of the parameters. Else an object holds exactly one of these forms
  // (the checker names what is missing or extra; the schema says the same).
  std::vector<ParamForm> forms;
  std::string forms_text() const;  // "one of: inline arrays (\"positions\", …); …"
  Equivalence cycles;    // the nearest Cycles closure
  Equivalence pov;       // POV-Ray's native finish
  BlenderNodes blender_nodes;  // lobes: Blender's own node tree nearest the model, measured
  // Physics, as the literature states it (facet physics measures both):
  // f(l, v) = f(v, l); and directional albedo ≤ 1 for every incidence and roughness.
  bool reciprocal = false;
  bool energy_conserving = false;
  std::string physics_note;  // where the claim comes from, or why not
  // Lobes: build ρ in `ctx` from the material's values. Others: null.
  std::function<ir::Expr(LobeContext&)> build;
  // Layers (section "layer", a material's "layers"): ρ of the layer over `base`, the ρ of
  // everything under it (k_d ⊗ ρ_d + k_s ⊗ ρ_s and the layers below, 0 below the horizon),
  // built in `ctx` from the layer's values. Others: null.
  std::function<ir::Expr(LobeContext& ctx, const ir::Expr& base)> layer;

  // ---- POV-Ray's native finish: how `pov` is printed where it is exact (targets/pov.cpp)
  PovFinish pov_finish;
  // ---- end of POV-Ray's native finish

  const ParamDef* param(const std::string& name) const;

  // ---- What the scene layer reads of a model (scene/scene.cpp, scene/gltf.cpp),
  // so that it never compares a model's name: adding a model touches its entry only.
  // Objects, lights, attenuation laws: the kind of the model (set for the models of
  // that section, empty for every other model).
  std::optional<ObjectType> object_type;
  std::optional<LightType> light_type;
  std::optional<AttenuationLaw> attenuation_law;
  // Specular lobes: the GGX roughness α whose highlight is nearest this lobe's with
  // the given values, for the metallic–roughness fallback of a glTF export
  // (roughnessFactor = √α). Null: no equivalent; the export takes α = 1.
  std::function<double(const ModelSpec& lobe)> ggx_alpha;
  // Specular lobes: the lobe is glTF's own BRDF (Appendix B with KHR_materials_ior,
  // KHR_materials_specular and KHR_materials_clearcoat), its parameters glTF's: base_color,
  // metallic, roughness, ior, specular, specular_color, clearcoat, clearcoat_roughness. The
  // import reads them, the export writes its factors, maps and extensions as they are.
  bool gltf_brdf = false;
  // Specular lobes and layers over the emission (KHR_materials_clearcoat, "Emission": "the
  // clearcoat layer is on top of emission in the layering stack"): m_e's weight as a function
  // of n·v (its first parameter "NoV", a Float), for these values, named `function`; its other
  // parameters are the lobe's textured parameters it reads, named as the reflectance's inputs
  // (`name`_param, `name` the lobe's name in the material: "specular", "layer0"), each sampled
  // at the shading point. Null, or returning null: m_e as it is.
  std::function<ir::FunctionPtr(const ModelSpec& lobe, const std::string& name, const std::string& function)>
      emission_weight;
  // Layers that are a part of glTF's own BRDF (gltf_pbr, `gltf_brdf`): the gltf_pbr parameter
  // each of the layer's parameters is ({"color", "sheen_color"}, …; the first is the one whose 0
  // turns the part off), and the layer's place in glTF's stack, bottom up (KHR_materials_clearcoat:
  // "the clearcoat layer is on top of … sheen"): 1 the sheen, 2 the coat. gltf_brdf_lobe()
  // (material.h) folds such layers into the lobe, which the glTF export then writes as extensions.
  std::vector<std::pair<std::string, std::string>> gltf_brdf_params;
  int gltf_brdf_stack = 0;
  // Specular lobes and layers: whether these values have a layer with a normal of its own (a
  // clear coat), which a material may map apart from the base (Material::coat_normal_map). Null: none.
  std::function<bool(const ModelSpec& lobe)> coated;
  // Specular lobes whose tangent is the surface's texture-coordinate frame (the mesh's tangent:
  // KHR_materials_anisotropy's TBN) rather than the tangent rule on tangent_axis, for these
  // values: the coordinate set whose frame they read where no normal map names one, or nullopt
  // (the tangent rule). Every target then takes t = that frame's T made ⟂ n and b = w·(n × t).
  // Null: the tangent rule. `uv_tangent_param`: the parameter whose values ask for the frame,
  // which a message about a missing frame names ("anisotropy_strength").
  std::function<std::optional<int>(const ModelSpec& lobe)> uv_tangent;
  std::string uv_tangent_param;
  // Fresnel terms: the reflectance at normal incidence F(0) as a colour, where the
  // term states it. glTF's metallic workflow takes it as a conductor's base colour:
  // a specular-only material whose Fresnel term has it exports as a metal.
  // Null: the term states none (the material exports as a dielectric).
  std::function<std::array<double, 3>(const ModelSpec& fresnel)> normal_reflectance;
};

// A model chosen in a material, with every parameter's value (defaults applied).
struct ModelSpec {
  const ModelDef* def = nullptr;
  std::map<std::string, Value> values;
  std::set<std::string> given;  // the keys the document held; the other values are defaults
  const Value& at(const std::string& name) const;
};

// The geometric inputs a lobe can read, dot products of unit vectors each target
// computes: n, l, v, the tangent t, b = n × t, and the half vector
//   h = (l + v) / max(|l + v|, ε)
// (where l ≈ −v, both grazing, h is undefined; the floor keeps 1/|l + v| finite).
// Targets with vector types compute h with one vector normalization, which in
// SPIR-V is two instructions where deriving n·h, v·h, h·t and h·b from l·v and the
// other dots took ten; the lobes read the half-vector inputs through LobeContext,
// which adds the clamps rounding needs.
// c is the clear coat's own normal (KHR_materials_clearcoat, "Clearcoat": "`normal` … affects
// the top layer, but not the base"): the surface's own, unmapped normal, or the coat's normal
// map's. A lobe reads c·l, c·v and c·h only where c can differ from n (LobeContext::coat_normal),
// and a target computes them only for a material whose lobe reads them.
enum class Input { NoL, NoV, LoV, LoT, VoT, LoB, VoB, NoH, VoH, HoT, HoB, CoL, CoV, CoH };
const char* input_name(Input i);
const std::vector<std::string>& input_order();

// A parameter that comes from an image (catalog/texture.h): an input of the lobe
// function named as its constant would be (`diffuse_color`, `specular_fresnel_f0`),
// whose value each target samples at the shading point.
struct TexturedInput {
  std::string name;
  std::string key;  // its key path in the material: diffuse.color, specular.fresnel.f0
  ir::Type type = ir::Type::Float;
  Value value;  // its texture and factor
  Range range;  // the parameter's: the value is clamped to it
  // Non-empty: a Float input derived from the textured colour input of that name, max₃ of its
  // value (max(r, g, b) of the clamped colour, after it is sampled): every target computes it from
  // the colour it sampled, no image of its own (LobeContext::max_of). `value` is the colour's.
  std::string max_of;
};

// What a lobe's `build` sees: inputs, the material's parameter values as named
// constants (inputs where they come from an image), and the let-bindings of the
// lobe function being built.
class LobeContext {
 public:
  // `coat_normal`: the material gives its layers' own normal c apart from the lobes' n (a
  // normal map under the coat, or the coat's own normal map: Material::coat_normal_differs).
  // `key`: the spec's key path in the material, which messages name a textured parameter by
  // ("layers[0]"; empty: `lobe`, "diffuse" or "specular").
  LobeContext(const ModelSpec& spec, std::string lobe, ir::FunctionBuilder& fb, bool coat_normal = false,
              std::string key = "");
  // A lobe inside `parent`'s function (a mix layer's lobe): its values named `lobe`_…, its key
  // path `key`, its textured inputs `parent`'s.
  LobeContext(const ModelSpec& spec, std::string lobe, LobeContext& parent, std::string key);
  LobeContext(const LobeContext&) = delete;  // its textured inputs may live in another context
  LobeContext& operator=(const LobeContext&) = delete;

  ir::Expr input(Input i);
  ir::Expr NoL() { return input(Input::NoL); }
  ir::Expr NoV() { return input(Input::NoV); }
  ir::Expr LoV() { return input(Input::LoV); }
  // Half-vector quantities: min(n·h, 1), [v·h], h·t, h·b.
  ir::Expr NoH();
  ir::Expr VoH();
  ir::Expr HoT() { return input(Input::HoT); }
  ir::Expr HoB() { return input(Input::HoB); }

  ir::Expr number(const std::string& param);  // a named constant, e.g. specular_m
  // Parameter `param` of `spec` (the lobe's own or a sub-model's) as the IR value
  // `name`: a constant (one number where `grey` and the colour is grey), or an input
  // where it comes from an image.
  ir::Expr parameter(const ModelSpec& spec, const std::string& param, const std::string& name, bool grey = false);
  bool textured(const ModelSpec& spec, const std::string& param) const;
  // max₃ of colour parameter `param` of `spec`, taken as `name` where it comes from an image:
  // an input derived from the sampled colour (TexturedInput::max_of) named `name`_max; where
  // it is a colour, the constant `name`_max. Closed forms such as max₃(F) of a tinted Fresnel
  // read it (KHR_materials_specular, KHR_materials_sheen).
  ir::Expr max_of(const ModelSpec& spec, const std::string& param, const std::string& name);
  const std::vector<TexturedInput>& textured_inputs() const { return *textured_; }
  bool flag(const std::string& param) const;
  const std::string& choice(const std::string& param) const;
  const ModelSpec& model(const std::string& param) const;  // a Model/Object-kind parameter
  bool has(const std::string& param) const;
  ir::Expr let(const std::string& name, const ir::Expr& value) { return fb_.let(name, value); }
  // F(v·h) of the lobe's `fresnel` parameter.
  ir::Expr fresnel();
  // G of the lobe's `geometry` parameter, none or v_cavity; smith_ggx enters the
  // microfacet lobes as a visibility term instead (terms::visibility_smith_ggx).
  ir::Expr geometry();
  const std::string& lobe() const { return lobe_; }
  const std::string& key() const { return key_; }  // the spec's key path in the material
  // The material's values, for constants derived from them in closed form.
  const ModelSpec& spec() const { return spec_; }
  // Whether a layer with its own normal (a clear coat) reads c·l, c·v, c·h (Input::CoL …)
  // rather than n's: c differs from n.
  bool coat_normal() const { return coat_normal_; }

 private:
  const ModelSpec& spec_;
  std::string lobe_;
  ir::FunctionBuilder& fb_;
  bool coat_normal_ = false;
  std::string key_;
  std::vector<TexturedInput> own_textured_;
  std::vector<TexturedInput>* textured_ = &own_textured_;  // a child's: its parent's list
};

// ρ of the lobe `ctx` holds (its model's build), then its toon modifier where it has one.
ir::Expr lobe_rho(LobeContext& ctx);

// The whole catalog, in documentation order. Besides the shading vocabulary
// (diffuse, specular, fresnel, geometry, distribution, modifier, term, light,
// attenuation) it holds the scene vocabulary (camera, object), so scene files
// are checked and documented the same way.
const std::vector<ModelDef>& catalog();
const ModelDef* find_model(const std::string& section, const std::string& name);
// `def` with every parameter at its default (optional objects such as toon absent).
ModelSpec default_spec(const ModelDef& def);
std::vector<const ModelDef*> section(const std::string& name);
// The lobe `facet cost` gives every figure relative to (analysis/cost.h): Lambert's.
const ModelDef& cost_baseline_model();

// KHR_materials_sheen's directional albedo E(μ, r) as facet fits it (catalog/sheen.cpp,
// scripts/fit_sheen_albedo.py): for μ below `mu_end` (and above the previous piece's), E =
// clamp(exp(Σ a_k T_k(x)) − ε, 0, 1) with x = scale·m^power + offset, m = max(μ, mu_min). The
// pieces at sheen roughness r, E itself (for tests), ε, mu_min, and the fit's worst error against
// the integral on its check grid.
struct SheenAlbedoPiece {
  double mu_end = 1, power = 0.5, scale = 2, offset = -1;
  std::vector<double> coefficients;
};
std::vector<SheenAlbedoPiece> sheen_albedo_pieces(double sheen_roughness);
// The pieces' coefficients as series in r: on r's piece (r below `r_end`, at or above the
// previous piece's), a_k of μ piece p = Σ_j c[p][k][j] T_j(y), y = scale·√r + offset, r clamped
// into [r_min, 1]. sheen_albedo_pieces sums them for a roughness of numbers; a roughness from an
// image sums them at every pixel (gltf_sheen).
struct SheenAlbedoRPiece {
  double r_end = 1, scale = 2, offset = -1;
  std::vector<std::vector<std::vector<double>>> c;  // [μ piece][k][j]
};
const std::vector<SheenAlbedoRPiece>& sheen_albedo_r_pieces();  // built once
double sheen_albedo_r_min();
double sheen_albedo(double mu, double sheen_roughness);
double sheen_albedo_epsilon();
double sheen_albedo_mu_min();
double sheen_albedo_worst_error();
// The constants of KHR_materials_sheen's visibility at α: the README's l(x) = a / (1 + b x^c) +
// d x + e, each of a … e mixed by (1 − α)², and l(0.5): {a, b, c, d, e, l(0.5)}; the (p, q) of
// each mix(p, q, (1 − α)²), for a lobe that mixes them at every pixel (a roughness from an image).
std::array<double, 6> sheen_visibility_constants(double alpha);
std::array<std::pair<double, double>, 5> sheen_l_mix();

// The term functions of the catalog, one per term, each built once. Models
// compose them; tests and the docs reach them here.
namespace terms {
ir::FunctionPtr lambert();
ir::FunctionPtr minnaert();
ir::FunctionPtr minnaert_velvet();
ir::FunctionPtr oren_nayar();
ir::FunctionPtr phong();
ir::FunctionPtr blinn_phong();
ir::FunctionPtr schlick_power();
ir::FunctionPtr gaussian();
ir::FunctionPtr heidrich_seidel();
ir::FunctionPtr distribution_beckmann();
ir::FunctionPtr distribution_ggx();
ir::FunctionPtr distribution_trowbridge_reitz();
ir::FunctionPtr geometry_v_cavity();
// Terms whose inputs may be grey (one number) or coloured come in both types:
// a grey Fresnel term keeps the lobe scalar until k ⊗ ρ.
ir::FunctionPtr fresnel_schlick(ir::Type f0);
ir::FunctionPtr fresnel_exact();      // η > 1
ir::FunctionPtr fresnel_exact_tir();  // η ≤ 1: total internal reflection
ir::FunctionPtr microfacet(ir::Type F);
// Smith GGX as the visibility G / (4 (n·l)(n·v)), and ρ = π D V F (n·l) with it.
ir::FunctionPtr visibility_smith_ggx();
ir::FunctionPtr microfacet_visibility(ir::Type F);
// The height-correlated Smith GGX visibility of glTF 2.0 Appendix B.
ir::FunctionPtr visibility_smith_ggx_correlated();
// KHR_materials_anisotropy: Burley's anisotropic GGX D and the anisotropic height-correlated
// Smith visibility, of α_t along the (rotated) tangent and α_b along the bitangent.
ir::FunctionPtr distribution_ggx_anisotropic();
ir::FunctionPtr visibility_smith_ggx_correlated_anisotropic();
// KHR_materials_sheen (catalog/sheen.cpp): the "Charlie" D and visibility (the latter taking
// sheen_visibility_constants() after n·l and n·v), and the fit of the sheen's directional albedo,
// log(E + ε) as a Chebyshev series of one piece of μ (sheen_albedo_pieces()).
ir::FunctionPtr distribution_charlie();
ir::FunctionPtr visibility_charlie();
ir::FunctionPtr sheen_albedo_series();
// The layering operators (catalog section "layering"): fresnel_w = (1 − |v·h|)^5; Schlick's
// F with a free f90; fresnel_mix, conductor_fresnel and mix as glTF 2.0 Appendix B and
// KHR_materials_specular define them. A grey F keeps them scalar (fresnel_mix's max(F) is F).
ir::FunctionPtr fresnel_weight();
ir::FunctionPtr fresnel_schlick_f90(ir::Type f0);
ir::FunctionPtr fresnel_mix(ir::Type F, ir::Type base);
ir::FunctionPtr conductor_fresnel(ir::Type f0);
ir::FunctionPtr mix_by(ir::Type type);
ir::FunctionPtr blinn(ir::Type F);
ir::FunctionPtr ward();
ir::FunctionPtr ward_nvidia();
ir::FunctionPtr toon(ir::Type rho);       // smoothstep over [cutoff ± width/2]
ir::FunctionPtr toon_hard(ir::Type rho);  // width 0: a step at cutoff
ir::FunctionPtr attenuation_inverse_square();
ir::FunctionPtr attenuation_polynomial();
// KHR_lights_punctual's recommended window: att(d) = clamp(1 − (d/r)⁴, 0, 1) / d².
ir::FunctionPtr attenuation_inverse_square_range();
ir::FunctionPtr spot_cone();
}  // namespace terms

}  // namespace facet
