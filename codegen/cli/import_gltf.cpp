// facet import-gltf: turn a glTF 2.0 scene (.gltf, .glb) into a facet scene file.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "scene/gltf.h"
#include "scene/scene.h"

using nlohmann::json;

namespace facet::cli {
namespace {

std::string gi_in, gi_out, gi_default;
bool gi_inline = false;
double gi_lumens_per_watt = kLumensPerWatt;

int run_import_gltf() {
  GltfImportOptions opt;
  if (!gi_default.empty()) opt.default_material = load_material(gi_default);
  opt.output = gi_out;
  opt.lumens_per_watt = gi_lumens_per_watt;
  std::vector<std::string> notes;
  std::vector<GltfImportFile> files;  // the images the glTF held and those baked, then the scene: all or none
  Scene s = import_gltf(gi_in, opt, notes, &files);
  for (const auto& n : notes) std::cerr << "note: " << n << "\n";
  if (gi_inline) {
    size_t triangles = 0;
    for (const auto& o : s.objects) triangles += o.mesh ? o.mesh->triangles.size() : 0;
    if (triangles >= 500'000) progress(fmt::format("writing {}: {} triangles inline", gi_out, triangles));
  }
  json doc = to_json(s, gi_out);
  if (gi_inline) {  // the arrays themselves, the materials' images still relative to the scene file
    json materials = doc.value("materials", json());
    doc = to_json(s);
    if (!materials.is_null()) doc["materials"] = materials;
  }
  files.push_back({gi_out, doc.dump(1) + "\n"});
  write_import_files(files);
  fmt::print(stderr, "{}: {} objects, {} materials, {} lights\n", gi_out, s.objects.size(), s.materials.size(),
             s.lights.size());
  return 0;
}
}  // namespace

Command import_gltf_command(CLI::App& app) {
  auto* gi = app.add_subcommand("import-gltf", "Turn a glTF 2.0 scene (.gltf, .glb) into a facet scene file");
  gi->add_option("scene", gi_in, "The glTF file")->required();
  gi->add_option("-o,--output", gi_out, "The facet scene (JSON)")->required();
  gi->add_option("--default-material", gi_default,
                 "A facet material for primitives without one (default: glTF's default material, white metal)");
  gi->add_option("--lumens-per-watt", gi_lumens_per_watt,
                 "The luminous efficacy that turns the file's candela and lux into facet's radiometric light colour "
                 "(Blender's and glTF-Blender-IO's 683; 1 keeps photometric units)")
      ->check(CLI::Range(1e-3, 1e6));
  gi->add_flag("--inline", gi_inline,
               "Write each mesh's positions, normals and triangles into the scene file instead of referencing the "
               "glTF file");
  gi->footer(
      "Meshes (node transforms as glTF composes them: normals by the inverse transpose, mirrors reverse the\n"
      "winding; skins at the file's pose, morph targets at its weights), the first camera (perspective or\n"
      "orthographic), KHR_lights_punctual lights (C = colour · intensity / (683 lm/W · π): Blender's units;\n"
      "range as the extension's window) and the materials: FACET_material exactly, else glTF's own BRDF, the\n"
      "catalog's gltf_pbr lobe (glTF 2.0 Appendix B with KHR_materials_ior, _specular, _sheen and _clearcoat),\n"
      "every factor and map as the file gives it; alphaMode MASK as a cut-out, BLEND opaque; glTF's\n"
      "default material where a primitive has none. What is approximate or ignored (extensions facet does not\n"
      "implement, per material) is printed; a file that requires one is refused. Textures may read any\n"
      "TEXCOORD_n, each with its KHR_texture_transform. baseColorTexture, metallicRoughnessTexture (B, G),\n"
      "specularTexture (A), clearcoatTexture (R) and clearcoatRoughnessTexture (G) become textured\n"
      "parameters; the images\n"
      "a GLB or data URI holds, and those the import bakes (the occlusion's ambient term), are\n"
      "written to OUTPUT_STEM.textures/ beside the scene; external images are referenced where they are. A glTF\n"
      "without lights gets a headlight (a point light at the camera), as the notes say.\n"
      "The scene file references the glTF file's triangles rather than copying them, so it stays a few kB:\n"
      "each mesh object is {\"type\": \"mesh\", \"gltf\": FILE, \"node\": N} (\"primitive\": P where the node's mesh\n"
      "has several), FILE relative to the scene file; facet reads the node's mesh in its world transform.\n"
      "A scene file may also say \"mesh\": N (a mesh as it is), and name a node or mesh instead of N. Keep\n"
      "the glTF file beside the scene (or give --inline, for the arrays themselves). Example:\n"
      "  facet import-gltf examples/scenes/three_meshes.gltf -o scene.json && facet validate --scene scene.json");
  return {gi, [] { return run_import_gltf(); }};
}

}  // namespace facet::cli
