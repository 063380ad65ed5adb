// facet — the renderers' harness: every file of codegen/renderers/harness/ (the
// Cycles scripts, the GL ray-casting shaders), embedded at build time.
#pragma once

#include <map>
#include <string>

#include "core/template.h"

namespace facet {

// Every file of codegen/renderers/harness/, by name (e.g. "cycles_render.py").
const std::map<std::string, std::string>& embedded_harness();

// Harness file `name` with its placeholders filled (core/template.h).
inline std::string render_harness(const std::string& name, const std::map<std::string, std::string>& values = {}) {
  return fill_embedded(embedded_harness(), name, values);
}

}  // namespace facet
