// facet — the check fuzz_scene and fuzz_gltf share: an accepted scene's names are data in
// the POV-Ray scene it becomes.
#pragma once

#include <string>

#include "catalog/material.h"
#include "fuzz_common.h"
#include "scene/scene.h"
#include "targets/targets.h"

namespace facet::fuzz {

// `s` as a POV-Ray scene (shaded with `material`), and again with every name replaced by
// a letter and a number (the scene's, its objects', its materials'): the names change comments and
// identifiers only (same_structure), and no nan or inf is printed (finite_literals).
inline void pov_scene_names_are_data(const char* what, const Scene& s, const Material& material) {
  const std::string named = generate_pov_files(s, &material, "fuzz.json", PovRoute::Auto, "fuzz").code;
  Scene plain = s;
  plain.name = "n";
  size_t k = 0;  // distinct names stay distinct: "o0", "o1", …
  for (auto& o : plain.objects) o.name = "o" + std::to_string(k++);
  k = 0;
  for (auto& [key, m] : plain.materials) m.name = "m" + std::to_string(k++);
  const std::string reference = generate_pov_files(plain, &material, "fuzz.json", PovRoute::Auto, "fuzz").code;
  same_structure(what, named, reference);
  finite_literals(what, reference);
}

}  // namespace facet::fuzz
