// facet's fuzz targets share one rule: bad input may only ever be refused with
// an InputError (which names the file and the key path, as the command line
// prints it). Any other exception escaping facet is a bug the fuzzer reports,
// like a crash, a hang or a sanitizer finding: a user would have seen
// "terminate called after throwing …" instead of an error message.
#pragma once

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "core/diagnostics.h"

namespace facet::fuzz {

template <typename F>
void refuse_only_with_input_errors(const char* what, F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    if (e.diagnostics().empty()) {
      std::fprintf(stderr, "fuzz: %s: an InputError without a diagnostic\n", what);
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: %s: not an InputError escaped: %s\n", what, e.what());
    std::abort();
  }
}

inline void fail(const char* what, const std::string& why, const std::string& line) {
  std::fprintf(stderr, "fuzz: %s: %s:\n%s\n", what, why.c_str(), line.c_str());
  std::abort();
}

// The lines of `text`, split at \n and at \r (which ends a // comment in GLSL too).
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines(1);
  for (char c : text) {
    if (c == '\n' || c == '\r') lines.emplace_back();
    else lines.back() += c;
  }
  return lines;
}

// A line's code: what precedes its "//" (every target comments with // alone), each run of
// identifier characters made one "w" and white space left out, so that two lines whose names
// differ compare equal when the names changed identifiers only.
inline std::string shape_of(const std::string& line) {
  const std::string code = line.substr(0, line.find("//"));
  std::string shape;
  for (size_t i = 0; i < code.size();) {
    if (std::isalnum(static_cast<unsigned char>(code[i])) || code[i] == '_') {
      while (i < code.size() && (std::isalnum(static_cast<unsigned char>(code[i])) || code[i] == '_')) ++i;
      shape += 'w';
    } else if (std::isspace(static_cast<unsigned char>(code[i]))) {
      ++i;
    } else {
      shape += code[i++];
    }
  }
  return shape;
}

// The injection oracle (issue 28): `named` is a target's code for a material or scene with
// names from the fuzzer, `plain` the same with plain names ("n"). The names may change
// comments (a long one wraps over more comment lines) and identifiers (a longer one wraps a
// line of code at another place), nothing else: the same code, token for token, but for
// identifier characters and line breaks, and no more lines ending in a backslash (which would
// splice the next line into a comment in every C preprocessor: GLSL, HLSL, OSL).
inline void same_structure(const char* what, const std::string& named, const std::string& plain) {
  struct Code {
    std::string shape;                 // every line's shape_of(), one after another
    std::vector<size_t> line_at;       // the line each character of `shape` came from
    std::vector<std::string> lines;
    size_t splices = 0;
  };
  auto code = [](const std::string& text) {
    Code c;
    c.lines = lines_of(text);
    for (size_t k = 0; k < c.lines.size(); ++k) {
      const std::string& line = c.lines[k];
      if (!line.empty() && line.back() == '\\') ++c.splices;
      const size_t first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line.compare(first, 2, "//") == 0) continue;  // a comment line
      const std::string s = shape_of(line);
      c.shape += s;
      c.line_at.insert(c.line_at.end(), s.size(), k);
    }
    return c;
  };
  const Code a = code(named), b = code(plain);
  if (a.splices != b.splices) fail(what, "a name ends a line with a backslash", named.substr(0, 2000));
  size_t i = 0;
  while (i < a.shape.size() && i < b.shape.size() && a.shape[i] == b.shape[i]) ++i;
  if (i == a.shape.size() && i == b.shape.size()) return;
  auto line = [](const Code& c, size_t at) {
    return c.line_at.empty() ? std::string("(no code)") : c.lines[c.line_at[std::min(at, c.line_at.size() - 1)]];
  };
  fail(what, "a name changed the code", line(a, i) + "\n  instead of\n" + line(b, i));
}

// No non-finite literal reaches code: the words nan, inf and infinity outside comments.
inline void finite_literals(const char* what, const std::string& code) {
  for (const std::string& line : lines_of(code)) {
    const std::string c = line.substr(0, line.find("//"));
    for (size_t i = 0; i < c.size();) {
      if (!std::isalpha(static_cast<unsigned char>(c[i]))) {
        ++i;
        continue;
      }
      size_t j = i;
      std::string word;
      while (j < c.size() && (std::isalnum(static_cast<unsigned char>(c[j])) || c[j] == '_'))
        word += char(std::tolower(static_cast<unsigned char>(c[j++])));
      if ((i == 0 || !std::isalnum(static_cast<unsigned char>(c[i - 1]))) &&
          (word == "nan" || word == "inf" || word == "infinity"))
        fail(what, "a non-finite number in the code", line);
      i = j;
    }
  }
}

}  // namespace facet::fuzz
