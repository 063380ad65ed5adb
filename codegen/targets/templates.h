// facet — the printers' scaffolding: every file of templates/, embedded at build time.
#pragma once

#include <map>
#include <string>

#include "core/template.h"

namespace facet {

// Every file of templates/, by path relative to it (e.g. "glsl/library.glsl").
const std::map<std::string, std::string>& embedded_templates();

// Template `path` of templates/ with its placeholders filled (core/template.h).
inline std::string render_template(const std::string& path, const std::map<std::string, std::string>& values) {
  return fill_embedded(embedded_templates(), path, values);
}

}  // namespace facet
