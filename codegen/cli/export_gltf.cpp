// facet export-gltf: write a facet scene as glTF 2.0 with its facet materials.
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "scene/gltf.h"
#include "scene/scene.h"

using nlohmann::json;

namespace facet::cli {
namespace {

std::string ge_in, ge_out, ge_material;

int run_export_gltf() {
  Scene s = load_scene(ge_in);
  std::optional<Material> m;
  if (!ge_material.empty()) m = load_material(ge_material);
  std::vector<std::string> notes;
  export_gltf(s, m ? &*m : nullptr, ge_out, notes);
  for (const auto& n : notes) std::cerr << "note: " << n << "\n";
  return 0;
}
}  // namespace

Command export_gltf_command(CLI::App& app) {
  auto* ge = app.add_subcommand("export-gltf", "Write a facet scene as glTF 2.0 with its facet materials");
  ge->add_option("scene", ge_in, "The facet scene (JSON) or a built-in name")->required();
  ge->add_option("-o,--output", ge_out, "The glTF file: .gltf (one file) or .glb")->required();
  ge->add_option("--material", ge_material, "A facet material for objects without one");
  ge->footer(
      "Materials carry the whole facet description (FACET_material) beside glTF's own: a gltf_pbr lobe as its\n"
      "factors, maps, KHR_materials_ior, _specular, _sheen and _clearcoat exactly, a classic model as the nearest\n"
      "metallic–roughness; spheres and planes are tessellated and keep their exact definition (FACET_object). The\n"
      "materials' images are copied to OUTPUT_STEM.textures/ beside a .gltf or held in a .glb; an sRGB diffuse\n"
      "colour map is also the fallback's baseColorTexture. Example:\n"
      "  facet export-gltf examples/scenes/three_meshes.json -o three_meshes.gltf");
  return {ge, [] { return run_export_gltf(); }};
}

}  // namespace facet::cli
