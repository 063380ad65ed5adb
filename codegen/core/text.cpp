#include "core/text.h"

#include <fmt/format.h>

namespace facet {

namespace {

// The code point at `text[i]` and its length in bytes (invalid UTF-8 as one byte: facet's
// JSON reader refuses it before here, so this only keeps the walk going).
std::pair<char32_t, size_t> decode(std::string_view text, size_t i) {
  const auto b = static_cast<unsigned char>(text[i]);
  size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 1;
  if (i + n > text.size()) n = 1;
  if (n == 1) return {b, 1};
  char32_t c = b & (0x7F >> n);
  for (size_t k = 1; k < n; ++k) c = (c << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
  return {c, n};
}

bool breaks(char32_t c) { return c < 0x20 || c == 0x7F || c == 0x85 || c == 0x2028 || c == 0x2029; }

const char* name_of(char32_t c) {
  switch (c) {
    case 0x0A: return "a line feed";
    case 0x0D: return "a carriage return";
    case 0x00: return "a NUL";
    case 0x09: return "a tab";
    case 0x1B: return "an escape";
    case 0x7F: return "a delete";
    case 0x85: return "a next-line";
    case 0x2028: return "a line separator";
    case 0x2029: return "a paragraph separator";
    default: return "a control character";
  }
}

}  // namespace

std::optional<LineBreak> line_break(std::string_view text) {
  size_t at = 0;
  for (size_t i = 0; i < text.size(); ++at) {
    const auto [c, n] = decode(text, i);
    if (breaks(c)) return LineBreak{at, c};
    i += n;
  }
  return std::nullopt;
}

std::string describe(const LineBreak& b) {
  return fmt::format("contains U+{:04X} ({}) at character {}", static_cast<unsigned>(b.code), name_of(b.code), b.at);
}

std::string one_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const auto [c, n] = decode(text, i);
    if (c < 0x20) out += fmt::format("\xE2\x90{:c}", static_cast<char>(0x80 + c));  // U+2400 + c
    else if (c == 0x7F) out += "\xE2\x90\xA1";                                       // ␡ U+2421
    else if (breaks(c)) out += "\xE2\x90\xA4";                                       // ␤ U+2424
    else out.append(text.substr(i, n));
    i += n;
  }
  return out;
}

std::string printable_lines(std::string_view text) {
  std::string out;
  for (size_t start = 0;;) {
    const size_t end = text.find('\n', start);
    out += one_line(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) return out;
    out += '\n';
    start = end + 1;
  }
}

std::string quoted_literal(std::string_view text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '\\' || ch == '"') out += '\\';
    out += ch;
  }
  return out + "\"";
}

}  // namespace facet
