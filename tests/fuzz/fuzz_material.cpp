// libFuzzer target: material files. Every document either parses into a
// material from which every target generates, or is refused with an InputError.
// The document is read as if it lay in examples/textured/, so that the seeds'
// textures ("../textures/…") are found and textured materials are generated too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "catalog/material.h"
#include "fuzz_common.h"
#include "scene/scene.h"
#include "targets/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  const std::string file = FACET_SOURCE_DIR "/examples/textured/fuzz.json";
  facet::fuzz::refuse_only_with_input_errors("material", [&] {
    facet::Material m = facet::parse_material(facet::parse_json(text, file), file);
    for (facet::Target t : facet::all_targets()) {
      // POV-Ray's scene and library may read files beside them (a textured material's images):
      // the files' API, as facet generate calls it.
      if (t == facet::Target::Pov) {
        (void)facet::generate_pov_files(facet::default_scene(), &m, file, facet::PovRoute::Auto, "fuzz");
        (void)facet::generate_pov_library(m, file, facet::PovRoute::Auto, "fuzz");
        continue;
      }
      facet::GenerateOptions o;
      o.target = t;
      (void)facet::generate(m, o);
      o.library = true;
      (void)facet::generate(m, o);
    }
  });
  return 0;
}
