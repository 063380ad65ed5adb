// libFuzzer target: material files. Every document either parses into a
// material from which every target generates, or is refused with an InputError. What is
// accepted is held to more (issue 28): its name changes no line of any target's code but
// comments and identifiers (fuzz_common.h same_structure), no code holds nan or inf, and
// the reference's numbers are finite at hard direction sets.
// The document is read as if it lay in examples/textured/, so that the seeds'
// textures ("textures/…") are found and textured materials are generated too.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "fuzz_common.h"
#include "reference/interpreter.h"
#include "scene/scene.h"
#include "targets/targets.h"

namespace {

// Every target's code (and POV-Ray's scene and library), one string each, in one order.
std::vector<std::string> all_code(const facet::Material& m, const std::string& file) {
  std::vector<std::string> out;
  for (facet::Target t : facet::all_targets()) {
    // POV-Ray's scene and library may read files beside them (a textured material's images):
    // the files' API, as facet generate calls it.
    if (t == facet::Target::Pov) {
      out.push_back(facet::generate_pov_files(facet::default_scene(), &m, file, facet::PovRoute::Auto, "fuzz").code);
      out.push_back(facet::generate_pov_library(m, file, facet::PovRoute::Auto, "fuzz").code);
      continue;
    }
    facet::GenerateOptions o;
    o.target = t;
    out.push_back(facet::generate(m, o));
    o.library = true;
    out.push_back(facet::generate(m, o));
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  const std::string file = FACET_SOURCE_DIR "/examples/textured/fuzz.json";
  facet::fuzz::refuse_only_with_input_errors("material", [&] {
    facet::Material m = facet::parse_material(facet::parse_json(text, file), file);
    const std::vector<std::string> named = all_code(m, file);
    // The same material named "n": the fuzzer's name may change comments and identifiers only.
    facet::Material plain = m;
    plain.name = "n";
    const std::vector<std::string> reference = all_code(plain, file);
    for (size_t i = 0; i < named.size(); ++i) {
      facet::fuzz::same_structure("material: a name in the generated code", named[i], reference[i]);
      facet::fuzz::finite_literals("material: the generated code", reference[i]);
    }
    // The reference's numbers are finite at every direction set, the hard ones included:
    // normal incidence, grazing (n·l, n·v at 1e-4 and 0), l = v, l = −v, below the horizon.
    const facet::Reference ref(m);
    const facet::Vec3 n{0, 0, 1};
    const facet::Vec3 dirs[] = {{0, 0, 1}, {0.6, 0, 0.8}, {-0.6, 0, 0.8}, {0, 0.9999999950, 1e-4},
                                {1, 0, 0},  {0, -1, 0},  {0.3, 0.4, -0.866}, {0.48, 0.64, 0.6}};
    const facet::Vec3 t = facet::tangent_rule(n, facet::Vec3(m.tangent_axis));
    for (const auto& l : dirs)
      for (const auto& v : dirs)
        for (double u : {0.0, 0.37, 0.999}) {  // a textured parameter as rendering samples it
          facet::ShadingInputs in = facet::shading_inputs(n, l, v, t);
          ref.sample_textures({{{u, 1 - u}, {1 - u, u}}}, in);
          for (double x : ref.reflectance(in))
            if (!std::isfinite(x)) facet::fuzz::fail("material: the reference", "not finite", text.substr(0, 2000));
        }
  });
  return 0;
}
