// libFuzzer target: material files. Every document either parses into a
// material from which every target generates, or is refused with an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "catalog/material.h"
#include "fuzz_common.h"
#include "targets/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  facet::fuzz::refuse_only_with_input_errors("material", [&] {
    facet::Material m = facet::parse_material(facet::parse_json(text, "fuzz.json"), "fuzz.json");
    for (facet::Target t : facet::all_targets()) {
      facet::GenerateOptions o;
      o.target = t;
      (void)facet::generate(m, o);
      o.library = true;
      (void)facet::generate(m, o);
    }
  });
  return 0;
}
