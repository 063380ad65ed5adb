// facet — a material: the one description every target is generated from.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "catalog/catalog.h"
#include "catalog/texture.h"
#include "core/diagnostics.h"

namespace facet {

using RGB = std::array<double, 3>;

struct Material {
  std::string name;    // from the file, or the file's stem
  std::string source;  // the file it was read from ("" when built in code)
  // m_a and m_e: the colours, or, where `ambient_texture` / `emission_texture` is set, the
  // factor of the image's value (catalog/texture.h; docs/textures.md).
  RGB ambient{0, 0, 0};
  RGB emission{0, 0, 0};
  std::shared_ptr<const TextureRef> ambient_texture, emission_texture;
  std::optional<ModelSpec> diffuse;
  std::optional<ModelSpec> specular;
  // The layers over the lobes (catalog section "layer"), the first lowest: each weights what lies
  // under it — k_d ⊗ ρ_d + k_s ⊗ ρ_s and the layers before it — by what it reflects itself
  // (ModelDef::layer), and those with a layer over the emission dim m_e (ModelDef::emission_weight).
  std::vector<ModelSpec> layers;
  RGB tangent_axis{0, 1, 0};
  // A tangent-space normal map (catalog/texture.h, docs/textures.md): both lobes shade
  // with the mapped normal.
  std::optional<NormalMap> normal_map;
  // The normal map of the layers with a normal of their own (a clear coat: ModelDef::coated;
  // KHR_materials_clearcoat's clearcoatNormalTexture), on the same tangent frame as normal_map
  // (the same texture coordinate set). Without it those layers take the surface's own, unmapped
  // normal.
  std::optional<NormalMap> coat_normal_map;
  // Whether the layers with a normal of their own shade with another normal than the lobes':
  // their own map's, or the surface's own where the lobes' is mapped (KHR_materials_clearcoat:
  // "no normal mapping is applied to the clear coat layer, even if normal mapping is applied to
  // the base material").
  bool coat_normal_differs() const { return normal_map || coat_normal_map; }
  // Whether the specular lobe or a layer has a layer with a normal of its own (ModelDef::coated).
  bool coated() const;
  // Whether the lobes' tangent is the texture-coordinate frame's (ModelDef::uv_tangent: glTF's
  // anisotropy turns from the mesh's tangent) rather than the tangent rule on tangent_axis.
  bool lobes_uv_tangent() const { return uv_tangent_set().has_value(); }
  // The texture coordinate set whose tangent frame the material reads (docs/textures.md,
  // "Tangent frames"): normal_map's, else coat_normal_map's (both read the same set), else the
  // one the lobes' uv_tangent names; nullopt where nothing reads a frame.
  std::optional<int> frame_uv() const {
    if (normal_map) return normal_map->texture().uv;
    if (coat_normal_map) return coat_normal_map->texture().uv;
    return uv_tangent_set();
  }
  // The key that asks for that frame, for messages: "normal_map", "coat_normal_map" or the lobe's.
  std::string frame_key() const {
    if (normal_map) return "normal_map";
    if (coat_normal_map) return "coat_normal_map";
    return specular ? "specular." + specular->def->uv_tangent_param : "specular";
  }
  // glTF's alphaMode MASK (glTF 2.0 §3.9.4): where `alpha_cutoff` is set the surface is there
  // only where alpha ≥ alpha_cutoff, and camera and shadow rays pass where it is not. `alpha`
  // is a number in [0, 1] or an image's channel times a factor (catalog/texture.h), read only
  // with a cutoff. Without one the surface is opaque.
  Value alpha = opaque_alpha();
  std::optional<double> alpha_cutoff;
  bool masked() const { return alpha_cutoff.has_value(); }
  // The lobes' own frame set (ModelDef::uv_tangent), nullopt with the tangent rule.
  std::optional<int> uv_tangent_set() const {
    return specular && specular->def->uv_tangent ? specular->def->uv_tangent(*specular) : std::nullopt;
  }
  static Value opaque_alpha() {
    Value v;
    v.kind = ParamKind::Number;
    v.number = 1;
    return v;
  }
};

// The parameter "alpha" is: a number in [0, 1], texturable.
const ParamDef& alpha_param();

// Checks `doc` against the catalog; every problem becomes a Diagnostic naming
// `file` and the key path. Throws InputError with all of them. Texture files are named
// relative to, and must lie inside, `folder` (empty: `file`'s folder) or an allowed one.
Material parse_material(const nlohmann::json& doc, const std::string& file, const std::string& folder = "");
Material load_material(const std::string& path);

// A material of one lobe: `spec` as the diffuse or the specular lobe (by its
// model's section), nothing else, named `name`. The sweep, the physics checks,
// the cost table and the docs build their materials with it.
// m_a or m_e (`ambient`) as a parameter value: its colour, or its image and factor.
Value material_term(const Material& m, bool ambient);

Material lobe_material(const ModelSpec& spec, const std::string& name);
// One material per lobe model of the catalog (every diffuse and specular model),
// the lobe alone at its defaults, named after the model, in catalog order: what
// `facet cost` measures and `facet docs` shows when given no material.
std::vector<Material> model_materials();

// `m` as glTF's own BRDF alone: its gltf_pbr specular lobe (ModelDef::gltf_brdf; no diffuse lobe,
// k_s white, no toon) with its layers folded in where each is a part of that BRDF
// (ModelDef::gltf_brdf_params) lying where glTF's stack puts it — above the lobe's own parts, each
// part once — so that the result is the same reflectance. nullopt otherwise, `why` saying what
// glTF's BRDF cannot hold (empty where `m` has no gltf_pbr lobe at all).
std::optional<ModelSpec> gltf_brdf_lobe(const Material& m, std::string* why = nullptr);

// The canonical JSON form (every default written out), which parses back to an
// equal material.
nlohmann::json to_json(const Material& m);
// One model's object: {"model": name, …every parameter} (no "model" if !with_model).
nlohmann::json spec_json(const ModelSpec& s, bool with_model = true);

// A parameter's default as `facet models --json` and the docs print it: null where
// there is none (required meshes, optional objects such as toon).
nlohmann::json default_json(const ParamDef& p);

// A JSON Schema (draft 2020-12) of material files, generated from the catalog.
nlohmann::json material_schema();

// Schema fragments for a parameter, and for a model's object (with `key` naming
// its discriminator, "model" or "type"; empty for none).
nlohmann::json param_schema(const ParamDef& p);
nlohmann::json model_schema(const ModelDef& m, const std::string& key);

// A name usable as an identifier in GLSL, OSL and POV-Ray, and in file names: letters, digits
// and "_"; past kIdentifierMax characters, its first ones and a hash of the whole name.
constexpr size_t kIdentifierMax = 64;
std::string identifier(const std::string& name);

}  // namespace facet
