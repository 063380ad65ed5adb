// facet — a material compiled to IR functions, ready for the printers and the
// C++ reference.
#pragma once

#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/ir.h"

namespace facet {

// The names of m_a and m_e where they come from images: textured inputs that the
// reflectance does not read (MaterialProgram::textured), the names every target gives them.
inline constexpr const char* kAmbientInput = "material_ambient";
inline constexpr const char* kEmissionInput = "material_emission";

struct MaterialProgram {
  Material material;
  ir::FunctionPtr diffuse;      // rho_diffuse(inputs…), or null
  ir::FunctionPtr specular;     // rho_specular(inputs…), or null
  // layer<i>_<model>(base, inputs…), Material::layers' ρ over `base`, the ρ under it, in order.
  std::vector<ir::FunctionPtr> layers;
  ir::FunctionPtr reflectance;  // k_d ⊗ ρ_d + k_s ⊗ ρ_s under the layers, 0 below the horizon
  std::vector<std::string> inputs;  // reflectance's parameters: input_order()'s, then `textured`'s
  // The parameters that come from images, each an input of reflectance (and of the
  // lobe that reads it) whose value the target samples at the shading point.
  // m_a and m_e, where they come from images, come last (kAmbientInput, kEmissionInput).
  std::vector<TexturedInput> textured;
  // m_e's weight under the layers over it, emission_weight(NoV[, the textured inputs it reads,
  // by name]) with n·v of the surface's own (unmapped) normal, or null where nothing lies over
  // the emission (ModelDef::emission_weight; set only where the material emits). Every target
  // multiplies m_e by it.
  ir::FunctionPtr emission_weight;
  // Where more than one layer lies over the emission: each one's weight, which emission_weight
  // multiplies (functions of this material's values, as the lobes are).
  std::vector<ir::FunctionPtr> emission_weights;

  bool uses(const std::string& input) const;
  // Whether the material samples images: textured parameters or a normal map.
  bool has_textures() const { return !textured.empty() || has_uv_frame(); }
  // Whether the lobes read a normal map's normal.
  bool normal_mapped() const { return material.normal_map.has_value(); }
  // Whether the coat reads its own normal map's normal (Material::coat_normal_map).
  bool coat_normal_mapped() const { return material.coat_normal_map.has_value(); }
  // Whether the shading reads the tangent frame of a texture coordinate set: a normal map, the
  // lobes' or the coat's, or lobes whose tangent is that frame's (Material::frame_uv).
  bool has_uv_frame() const { return material.frame_uv().has_value(); }
  // Whether the lobes read the frame's tangent as t (and b = w·(n × t), w its handedness) in
  // place of the tangent rule (Material::lobes_uv_tangent; KHR_materials_anisotropy).
  bool uv_tangent() const { return material.lobes_uv_tangent() && uses_tangent(); }
  // Whether a textured input reads the surface's vertex colour (catalog/texture.h): every
  // target then takes the vertex colour as an input of its sampling (facet_color0).
  bool uses_vertex_color() const;
  // Whether `input` (a name of `inputs`) is a textured parameter rather than a dot product.
  bool is_textured(const std::string& input) const;
  bool uses_tangent() const {
    return uses("LoT") || uses("VoT") || uses("LoB") || uses("VoB") || uses("HoT") || uses("HoB");
  }
  bool uses_bitangent() const { return uses("LoB") || uses("VoB") || uses("HoB"); }
  bool uses_half_vector() const {
    return uses("NoH") || uses("VoH") || uses("HoT") || uses("HoB") || uses("CoH");
  }
  // Whether the reflectance reads the clear coat's own normal c (catalog.h, Input::CoL …):
  // every target's facet_reflect then takes c after t, the surface's own normal where the
  // lobes read a normal map's (Material::coat_normal_differs).
  bool uses_coat_normal() const { return uses("CoL") || uses("CoV") || uses("CoH"); }
  // Every function to print, callees first (the light functions included).
  std::vector<ir::FunctionPtr> functions() const;
  std::vector<ir::NodePtr> constants() const;
};

MaterialProgram compile(const Material& m);
// Throws InputError naming each image `m` reads (file and key: its textured parameters, its
// normal maps), "an image texture, " or "a normal map, " then `why`, for what shades without
// texture coordinates (the sweeps, facet cost's frame). Nothing where it reads none.
void require_no_images(const Material& m, const std::string& why);
// One lobe of `p` without its colour, ρ_d or ρ_s, 0 below the horizon, taking n·l,
// n·v and the inputs the lobe reads (so k_d ⊗ ρ_d + k_s ⊗ ρ_s is k_d ⊗ this(diffuse) +
// k_s ⊗ this(specular)): for a target that applies k_d and k_s itself, as POV-Ray's
// colour maps do. Null where `p` has no such lobe.
ir::FunctionPtr lobe_reflectance(const MaterialProgram& p, bool specular);
// "Phong (n = 32)": the model's title and its numeric parameters, as the
// generated code's comments and the diagrams name a lobe.
std::string describe(const ModelSpec& s);

}  // namespace facet
