// libFuzzer target: scene files. Every document either parses into a scene
// that the POV-Ray scene generator and the reference ray caster (a few pixels,
// meshes through their BVH) take, or is refused with an InputError. The names in an
// accepted scene (the scene's, its objects', its materials') change no line of the POV-Ray
// scene but comments and identifiers (fuzz_pov_scene.h), which holds no nan or inf.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "fuzz_pov_scene.h"
#include "reference/raycaster.h"
#include "scene/scene.h"
#include "targets/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const facet::Material lambert = facet::model_materials().front();
  std::string text(reinterpret_cast<const char*>(data), size);
  facet::fuzz::refuse_only_with_input_errors("scene", [&] {
    facet::Scene s = facet::parse_scene(facet::parse_json(text, "fuzz.json"), "fuzz.json");
    facet::fuzz::pov_scene_names_are_data("scene: the POV-Ray scene", s, lambert);
    (void)facet::render_reference(lambert, s, 4, 4, 1);
  });
  return 0;
}
