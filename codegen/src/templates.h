// facet — the scaffolding files under templates/, embedded at build time.
#pragma once

#include <map>
#include <string>

namespace facet {

// Every file of templates/, by path relative to it (e.g. "glsl/fragment.glsl").
const std::map<std::string, std::string>& embedded_templates();
// Every file of codegen/renderers/ (the Cycles harness).
const std::map<std::string, std::string>& embedded_scripts();

// Fills {{name}} placeholders of template `path`. A placeholder without a value,
// or a value without a placeholder, is a bug and throws std::logic_error.
std::string render_template(const std::string& path, const std::map<std::string, std::string>& values);

}  // namespace facet
