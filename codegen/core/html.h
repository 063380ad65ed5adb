// Escaping for the HTML and SVG facet writes (the validation report, the docs,
// the diagrams), shared by the layers above.
#pragma once

#include <string>

namespace facet {

// <, >, & and " as entities: safe in element text and in double-quoted attributes.
inline std::string html_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

}  // namespace facet
