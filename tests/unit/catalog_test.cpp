// The catalog's structure, and the model × target coverage matrix: every
// example material generates for every target.
#include <cmath>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "catalog/catalog.h"
#include "catalog/material.h"
#include "targets/targets.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = FACET_SOURCE_DIR;

TEST(Catalog, HasEveryModelOfModelsMd) {
  std::set<std::string> want = {"diffuse/lambert", "diffuse/minnaert", "diffuse/minnaert_velvet",
                                "diffuse/oren_nayar", "specular/phong", "specular/blinn_phong",
                                "specular/gaussian", "specular/heidrich_seidel", "specular/beckmann",
                                "specular/cook_torrance", "specular/ggx", "specular/blinn",
                                "specular/ward", "specular/ward_nvidia", "fresnel/none",
                                "fresnel/schlick", "fresnel/exact", "geometry/none",
                                "geometry/v_cavity", "geometry/smith_ggx", "modifier/toon",
                                "modifier/schlick_approximation", "light/point", "light/directional",
                                "light/spot", "attenuation/none", "attenuation/inverse_square",
                                "attenuation/polynomial", "term/ambient", "term/emission"};
  std::set<std::string> have;
  for (const auto& m : catalog()) have.insert(m.section + "/" + m.name);
  for (const auto& w : want) EXPECT_TRUE(have.count(w)) << w;
}

TEST(Catalog, EveryLobeIsDocumentedCitedAndBuildable) {
  for (const auto& m : catalog()) {
    if (m.section != "diffuse" && m.section != "specular") continue;
    EXPECT_FALSE(m.title.empty()) << m.name;
    EXPECT_FALSE(m.citation.empty()) << m.name;
    EXPECT_FALSE(m.formula.empty()) << m.name;
    EXPECT_FALSE(m.doc.empty()) << m.name;
    EXPECT_FALSE(m.cycles.note.empty()) << m.name;
    EXPECT_FALSE(m.pov.note.empty()) << m.name;
    ASSERT_TRUE(m.build) << m.name;
    // The model with its documented start values is a valid material.
    nlohmann::json lobe = {{"model", m.name}};
    for (const auto& p : m.params)
      if (p.required && p.kind == ParamKind::Number) lobe[p.name] = p.fallback.number;
    Material mat = parse_material({{m.section, lobe}}, "catalog");
    for (Target t : all_targets()) {
      GenerateOptions o;
      o.target = t;
      EXPECT_NO_THROW(generate(mat, o)) << m.name << " → " << target_name(t);
    }
  }
}

// A lobe that reads the mesh's tangent frame names the parameter that asks for it, so a
// message about a mesh without that frame names a key of the material (Material::frame_key).
TEST(Catalog, FrameTangentLobesNameTheirParameter) {
  int lobes = 0;
  for (const auto& m : catalog()) {
    if (!m.uv_tangent) {
      EXPECT_TRUE(m.uv_tangent_param.empty()) << m.name;
      continue;
    }
    ++lobes;
    EXPECT_NE(m.param(m.uv_tangent_param), nullptr) << m.name << ": " << m.uv_tangent_param;
  }
  EXPECT_GT(lobes, 0);
}

TEST(Catalog, ParameterDefaultsAreInRange) {
  for (const auto& m : catalog()) {
    for (const auto& p : m.params) {
      if (p.kind == ParamKind::Number) {
        EXPECT_TRUE(p.range.contains(p.fallback.number)) << m.name << "." << p.name;
      }
    }
  }
}

TEST(Catalog, SceneModelsStateTheirKind) {
  // The scene layer builds objects, lights and attenuation laws from the kind the
  // catalog states, never from a model's name: each model of those sections has
  // one, every kind belongs to one model, and no other model has one.
  std::set<int> objects, lights, laws;
  for (const auto& m : catalog()) {
    EXPECT_EQ(m.object_type.has_value(), m.section == "object") << m.name;
    EXPECT_EQ(m.light_type.has_value(), m.section == "light") << m.name;
    EXPECT_EQ(m.attenuation_law.has_value(), m.section == "attenuation") << m.name;
    if (m.object_type) {
      EXPECT_TRUE(objects.insert(int(*m.object_type)).second) << m.name;
    }
    if (m.light_type) {
      EXPECT_TRUE(lights.insert(int(*m.light_type)).second) << m.name;
    }
    if (m.attenuation_law) {
      EXPECT_TRUE(laws.insert(int(*m.attenuation_law)).second) << m.name;
    }
  }
  EXPECT_EQ(objects.size(), 3u);
  EXPECT_EQ(lights.size(), 3u);
  EXPECT_EQ(laws.size(), 4u);  // none, inverse square, polynomial, inverse square within a range
}

TEST(Catalog, EverySpecularLobeHasAGltfRoughness) {
  // The glTF export's metallic–roughness fallback reads these; a lobe without
  // one would export as fully rough.
  for (const auto& m : catalog()) {
    EXPECT_EQ(bool(m.ggx_alpha), m.section == "specular") << m.name;
    if (m.ggx_alpha) {
      double alpha = m.ggx_alpha(default_spec(m));
      EXPECT_TRUE(std::isfinite(alpha) && alpha > 0) << m.name << ": α = " << alpha;
    }
    if (m.normal_reflectance) {
      EXPECT_EQ(m.section, "fresnel") << m.name;
    }
  }
  const ModelDef* schlick = find_model("fresnel", "schlick");
  ASSERT_TRUE(schlick && schlick->normal_reflectance);
  EXPECT_EQ(schlick->normal_reflectance(default_spec(*schlick)), (RGB{0.04, 0.04, 0.04}));
  EXPECT_DOUBLE_EQ(find_model("specular", "ggx")->ggx_alpha(default_spec(*find_model("specular", "ggx"))), 0.2);
}

// The examples of classic lobes, and of lobes under layers (examples/layered).
std::vector<fs::path> example_files() {
  std::vector<fs::path> out;
  for (const char* dir : {"examples/materials", "examples/layered"})
    for (const auto& e : fs::directory_iterator(kSource / dir))
      if (e.path().extension() == ".json") out.push_back(e.path());  // not the folder's README.md
  return out;
}

TEST(Examples, OnePerModelAtLeast) {
  std::set<std::string> seen;
  for (const auto& path : example_files()) {
    Material m = load_material(path.string());
    if (m.diffuse) seen.insert("diffuse/" + m.diffuse->def->name);
    if (m.specular) seen.insert("specular/" + m.specular->def->name);
    for (const auto& layer : m.layers) seen.insert("layer/" + layer.def->name);
  }
  for (const auto& m : catalog()) {
    if (m.section == "diffuse" || m.section == "specular" || m.section == "layer") {
      EXPECT_TRUE(seen.count(m.section + "/" + m.name)) << "no example uses " << m.name;
    }
  }
}

TEST(Examples, GenerateForEveryTargetAndScene) {
  for (const auto& path : example_files()) {
    Material m = load_material(path.string());
    for (Target t : all_targets()) {
      for (const char* scene : {"single", "shadows"}) {
        for (bool library : {false, true}) {
          GenerateOptions o;
          o.target = t;
          o.library = library;
          o.scene = load_scene(scene);
          std::string code;
          EXPECT_NO_THROW(code = generate(m, o)) << path << " " << target_name(t);
          EXPECT_GT(code.size(), 200u);
        }
      }
    }
  }
}

}  // namespace
}  // namespace facet
