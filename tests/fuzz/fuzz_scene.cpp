// libFuzzer target: scene files. Every document either parses into a scene
// that the POV-Ray scene generator and the reference ray caster (a few pixels,
// meshes through their BVH) take, or is refused with an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "reference/raycaster.h"
#include "scene/scene.h"
#include "targets/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const facet::Material lambert = facet::model_materials().front();
  std::string text(reinterpret_cast<const char*>(data), size);
  facet::fuzz::refuse_only_with_input_errors("scene", [&] {
    facet::Scene s = facet::parse_scene(facet::parse_json(text, "fuzz.json"), "fuzz.json");
    (void)facet::generate_pov_files(s, &lambert, "fuzz.json", facet::PovRoute::Auto, "fuzz");
    (void)facet::render_reference(lambert, s, 4, 4, 1);
  });
  return 0;
}
