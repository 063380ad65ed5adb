// facet — the C++ reference: the catalog's IR evaluated in double precision.
//
// Everything else in facet is compared with this: `facet eval`, the reference
// renderer, and (in the unit tests) closed forms written from the papers.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "catalog/material.h"
#include "catalog/program.h"
#include "catalog/texture.h"
#include "core/ir.h"
#include "core/vec.h"
#include "scene/scene.h"
#include "scene/tangents.h"  // tangent_rule

namespace facet {

// Evaluates IR functions. Colors are three lanes; floats use all three alike.
// prepare() is not thread-safe; run() on prepared functions is.
class Interpreter {
 public:
  Interpreter();
  ~Interpreter();
  Interpreter(Interpreter&&) noexcept;
  Interpreter& operator=(Interpreter&&) noexcept;
  int prepare(const ir::FunctionPtr& f);
  RGB run(int prepared, const RGB* args) const;
  RGB call(const ir::FunctionPtr& f, const std::vector<RGB>& args);  // prepare + run
  double call_float(const ir::FunctionPtr& f, const std::vector<double>& args);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The most parameters one material may take from images (MaterialProgram::textured).
inline constexpr size_t kMaxTexturedInputs = 16;

// The dot products a lobe reads (catalog.h: Input), and the values of the
// material's textured parameters at the shading point (in MaterialProgram::textured's order).
struct ShadingInputs {
  double NoL = 0, NoV = 0, LoV = 0, LoT = 0, VoT = 0, LoB = 0, VoB = 0;
  double NoH = 0, VoH = 0, HoT = 0, HoB = 0;  // h = (l + v) / max(|l + v|, ε)
  double CoL = 0, CoV = 0, CoH = 0;           // c the coat's own normal (catalog.h, Input)
  std::array<RGB, kMaxTexturedInputs> textured{};
  double get(const std::string& name) const;
  double get(int index) const;           // in input_order()
  static int index(const std::string& name);
};
ShadingInputs shading_inputs(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t);
// With the coat's own normal c (Material::coat_normal_differs); without, c = n. b = w·(n × t):
// w the texture frame's handedness where the lobes' t is that frame's (MaterialProgram::uv_tangent).
ShadingInputs shading_inputs(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t, const Vec3& c, double w = 1);

// The normal map's shading normal (docs/textures.md, "Normal maps"; glTF 2.0 §3.9.3):
// normalize(nt[0]·T + nt[1]·B + nt[2]·n), T = t Gram–Schmidt'd against n, B = w·(n × T).
Vec3 perturb_normal(const Vec3& n, const Vec3& t, double w, const std::array<double, 3>& nt);
// The anisotropic models' tangent under a normal map: t Gram–Schmidt'd against the mapped
// normal, normalize(t − n′(n′·t)).
Vec3 follow_normal(const Vec3& t, const Vec3& mapped);

class Reference {
 public:
  explicit Reference(const Material& m);
  const MaterialProgram& program() const { return program_; }
  const Material& material() const { return program_.material; }

  // The values of the textured parameters at texture coordinates uv[0] (set 0) and uv[1] (set 1),
  // on a surface of vertex colour `color0` (Object::color_at). True where a nearest-filtered
  // lookup lies on a texel's edge (catalog/texture.h).
  bool sample_textures(const std::array<std::array<double, 2>, 2>& uv, ShadingInputs& in,
                       const VertexColor& color0 = kWhiteVertexColor) const;
  // m_a ⊗ A + m_e·emission_weight(n·v), with m_a and m_e at the point where `in`'s textures
  // were sampled and n·v of the coat's normal (MaterialProgram::emission_weight): the surface's
  // own, or the coat's own normal map's.
  RGB emitted(const ShadingInputs& in, const RGB& scene_ambient, double NoV) const;
  // The material's normal map (it must have one) at texture coordinates `uv`, on the frame n, t, w:
  // perturb_normal of its n_t; `coat`: its coat's own normal map's (Material::coat_normal_map).
  // `fragile` as sample_textures's result.
  Vec3 mapped_normal(const std::array<std::array<double, 2>, 2>& uv, const Vec3& n, const Vec3& t, double w,
                     bool& fragile, bool coat = false) const;
  // k_d ⊗ ρ_d + k_s ⊗ ρ_s, zero below the horizon. Unit vectors; t ⟂ n.
  RGB reflectance(const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t) const;
  RGB reflectance(const Vec3& n, const Vec3& l, const Vec3& v) const;  // tangent rule
  RGB reflectance(const ShadingInputs& in) const;
  // The lobes alone: ρ without k and without the horizon rule. Zero if absent.
  RGB rho_diffuse(const ShadingInputs& in) const;
  RGB rho_specular(const ShadingInputs& in) const;
  // att(d) · spot for a light seen along unit l at distance d (catalog terms).
  double light_factor(const Light& light, const Vec3& l, double d) const;

 private:
  struct Prepared {
    int id = -1;
    std::vector<int> inputs;  // index into ShadingInputs::get order per parameter
  };
  Prepared prepare(const ir::FunctionPtr& f);
  RGB call(const Prepared& f, const ShadingInputs& in) const;
  MaterialProgram program_;
  Interpreter interp_;
  Prepared reflectance_, diffuse_, specular_, emission_weight_;
  std::vector<size_t> max_of_;  // per textured input: where it is a derived max₃, its colour's index
  int inverse_square_ = -1, polynomial_ = -1, windowed_ = -1, spot_ = -1;
};

}  // namespace facet
