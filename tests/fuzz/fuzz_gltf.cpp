// libFuzzer target: glTF import, .gltf text and .glb containers (the first
// byte chooses). Every file either imports into a scene or is refused with an
// InputError; no external file is read (import_gltf_data without a folder). An imported
// scene goes through the POV-Ray scene generator, its names (made one line by the import)
// changing nothing there but comments and identifiers (fuzz_pov_scene.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "fuzz_pov_scene.h"
#include "scene/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  // A .glb starts with its magic; anything else is read as .gltf JSON.
  bool binary = bytes.rfind("glTF", 0) == 0;
  facet::fuzz::refuse_only_with_input_errors("gltf", [&] {
    std::vector<std::string> notes;
    facet::GltfImportOptions options;
    facet::Scene s = facet::import_gltf_data(bytes, binary, binary ? "fuzz.glb" : "fuzz.gltf", "", options, notes);
    static const facet::Material lambert = facet::model_materials().front();
    facet::fuzz::pov_scene_names_are_data("gltf: the POV-Ray scene", s, lambert);
  });
  return 0;
}
