// facet — scaffolding files with {{name}} placeholders: the printers' templates
// (targets/templates.h) and the renderers' harness (renderers/harness.h).
#pragma once

#include <map>
#include <string>

namespace facet {

// Fills the {{name}} placeholders of `text`, the file `path` (named in errors).
// A placeholder without a value, or a value without a placeholder, is a bug and
// throws std::logic_error.
std::string fill_template(const std::string& path, const std::string& text,
                          const std::map<std::string, std::string>& values);

// The file `path` of an embedded folder, filled: throws std::logic_error when absent.
std::string fill_embedded(const std::map<std::string, std::string>& files, const std::string& path,
                          const std::map<std::string, std::string>& values);

}  // namespace facet
