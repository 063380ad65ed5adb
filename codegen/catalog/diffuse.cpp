// Diffuse models (ρ_d) of MODELS.md.
#include "catalog/catalog_internal.h"

namespace facet::catalog_detail {

void add_diffuse(std::vector<ModelDef>& all) {
  {
    ModelDef m;
    m.section = "diffuse";
    m.name = "lambert";
    m.title = "Lambert";
    m.citation = "Lambert 1760, \"Photometria\"";
    m.formula = "ρ_d = n·l";
    m.doc = "Light is scattered equally in all directions; the reflected radiance falls with the "
            "cosine of the angle of incidence. The reference for every other model: a white Lambert "
            "surface facing a light of colour C shows C.";
    m.cycles = exact("diffuse(N) (the Diffuse BSDF, f = 1/π) is the same lobe");
    m.pov = exact("finish { diffuse 1 brilliance 1 } with pigment k_d (POV has no 1/π)");
    m.blender_nodes = nodes_exact("Diffuse BSDF, Roughness 0, Color k_d");
    m.pov_finish.terms = {{"diffuse", PovFinishTerm::From::Weight, "", 0},
                          {"brilliance", PovFinishTerm::From::Fixed, "", 1}};
    m.pov_finish.pigment = "color";
    m.pov_finish.requirements = {
        {PovFinishRequirement::Kind::Absent, "toon", "", "the toon modifier is not a POV-Ray finish"}};
    m.build = [](LobeContext& c) { return ir::call(terms::lambert(), {c.NoL()}); };
    m.reciprocal = true;
    m.energy_conserving = true;
    m.physics_note = "f = 1/π: albedo exactly 1";
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "diffuse";
    m.name = "minnaert";
    m.title = "Minnaert";
    m.citation = "Minnaert 1941, \"The reciprocity principle in lunar photometry\", ApJ 93";
    m.formula = "ρ_d = (n·l)^k · max(n·v, ε)^(k−1)";
    m.doc = "A power of Lambert that keeps reciprocity. k = 1 is Lambert; k < 1 brightens the limb, "
            "as the full moon shows; k > 1 darkens it.";
    m.params = {number("k", "limb exponent; 1 is Lambert, below 1 brightens the limb", Range::positive_exponent(), 0.8)};
    m.cycles = none("Cycles has no Minnaert closure");
    m.pov = none("POV's brilliance gives (n·l)^k but not the (n·v)^(k−1) factor: function pigment");
    m.blender_nodes = nodes_none("no Blender node has the (n·v)^(k−1) factor");
    m.build = [](LobeContext& c) { return ir::call(terms::minnaert(), {c.NoL(), c.NoV(), c.number("k")}); };
    m.reciprocal = true;
    m.physics_note = "f ∝ (n·l)^(k−1)(n·v)^(k−1), symmetric (Minnaert built it for reciprocity); for k < 1 the "
                     "albedo grows without bound towards the limb";
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "diffuse";
    m.name = "minnaert_velvet";
    m.title = "Minnaert (velvet variant)";
    m.citation = "Losasso, \"Surface Reflection Models\", NVIDIA";
    m.formula = "ρ_d = (n·l)^(k+1) · (1 − n·v)^(1−k)";
    m.doc = "The form printed in the NVIDIA survey: the factor (1 − n·v)^(1−k) darkens the centre and "
            "lights the silhouette, the look of velvet. Not reciprocal; k = 1 is (n·l)².";
    m.params = {number("k", "velvet exponent in [0, 1]; smaller is more velvety", Range::closed(0, 1), 0.5)};
    m.cycles = none("Cycles' ashikhmin_velvet / sheen closures are different lobes");
    m.pov = none("function pigment");
    m.blender_nodes = nodes_none("no Blender node has this limb darkening (Velvet/Sheen are other lobes)");
    m.build = [](LobeContext& c) {
      return ir::call(terms::minnaert_velvet(), {c.NoL(), c.NoV(), c.number("k")});
    };
    m.physics_note = "an artistic limb term: (1 − n·v)^(1−k) is not symmetric in l and v";
    add_lobe_params(m);
    all.push_back(m);
  }
  {
    ModelDef m;
    m.section = "diffuse";
    m.name = "oren_nayar";
    m.title = "Oren–Nayar";
    m.citation = "Oren & Nayar 1994, \"Generalization of Lambert's Reflectance Model\", SIGGRAPH '94";
    m.formula = "ρ_d = (n·l) · (A + B · [cos φ] · sin α · tan β), A = 1 − 0.5 σ²/(σ² + q), "
                "B = 0.45 σ²/(σ² + 0.09), α = max(θ_i, θ_r), β = min(θ_i, θ_r)";
    m.doc = "Rough diffuse surfaces made of V-shaped Lambertian facets with slope deviation σ: "
            "back-scattering flattens the look of clay, plaster and the moon. The paper's "
            "qualitative model; q = 0.33, or 0.57 to account for interreflection. σ = 0 is Lambert.";
    m.params = {number("sigma", "facet slope deviation σ in radians", Range::scalar(), 0.3),
                flag("interreflection", "use q = 0.57 instead of 0.33 (interreflection)", false)};
    m.cycles = approximate("Cycles' oren_nayar closure is Fujii's improved model (with a multiscatter "
                           "term since 4.3), not the 1994 qualitative model");
    m.pov = none("function pigment");
    m.blender_nodes = nodes_approximate(
        "Diffuse BSDF (Fujii's improved Oren–Nayar with a multiscatter term), Roughness B/A, Color k_d",
        0.0755);
    m.build = [](LobeContext& c) {
      double q = c.flag("interreflection") ? 0.57 : 0.33;
      return ir::call(terms::oren_nayar(), {c.NoL(), c.NoV(), c.LoV(), c.number("sigma"), q});
    };
    m.reciprocal = true;
    m.physics_note = "symmetric in θ_i, θ_r (α = max, β = min); the qualitative fit lets a white surface reflect "
                     "a few % more than it receives at grazing incidence (Fujii 2012, \"A tiny improvement of "
                     "Oren-Nayar reflectance model\", notes this of the full model too)";
    add_lobe_params(m);
    all.push_back(m);
  }
}

}  // namespace facet::catalog_detail
