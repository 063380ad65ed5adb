// facet — text that facet prints into generated code: names in comments, file names in
// string literals. A name is data, never code (issue 28): a line break in a material's name
// would end the comment it is printed in, and what follows would be GLSL, OSL or POV-Ray.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace facet {

// A character that ends a line, or that a terminal or a compiler acts on: the C0 controls
// U+0000–U+001F (line feed, carriage return, NUL, ESC, …), DEL U+007F, and U+0085, U+2028 and
// U+2029, which WGSL takes for line breaks too (WGSL §3.2 "Blankspace and line breaks").
struct LineBreak {
  size_t at = 0;         // where, in characters (code points) from 0
  char32_t code = 0;     // which
};
// The first such character of UTF-8 `text`, or none.
std::optional<LineBreak> line_break(std::string_view text);
// "contains U+000A (a line feed) at character 3": what line_break() found, for an error message.
std::string describe(const LineBreak& b);
// `text` with each such character replaced by a visible stand-in (U+2400 + c for a C0 control,
// ␡ for DEL, ␤ for U+0085, U+2028 and U+2029): one line of printable text.
std::string one_line(std::string_view text);
// Lines of `text` made safe for a terminal: each line one_line() (NUL, ESC and the other
// controls a name or path may bring shown as stand-ins), the line feeds between them kept.
std::string printable_lines(std::string_view text);
// A double-quoted string literal of `text` for OSL and POV-Ray (C's escapes): `\` and `"`
// escaped. `text` must have no line_break() (checked where it was read).
std::string quoted_literal(std::string_view text);

}  // namespace facet
