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
#include <sstream>
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

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A line's code: what precedes its "//" (every target comments with // alone), each run of
// identifier characters made one "w", so that two lines whose names differ compare equal
// when the names changed identifiers only.
inline std::string shape_of(const std::string& line) {
  const std::string code = line.substr(0, line.find("//"));
  std::string shape;
  for (size_t i = 0; i < code.size();) {
    if (std::isalnum(static_cast<unsigned char>(code[i])) || code[i] == '_') {
      while (i < code.size() && (std::isalnum(static_cast<unsigned char>(code[i])) || code[i] == '_')) ++i;
      shape += 'w';
    } else {
      shape += code[i++];
    }
  }
  return shape;
}

// The injection oracle (issue 28): `named` is a target's code for a material with a name from
// the fuzzer, `plain` the same material named "n". The name may change comments (a long one
// wraps over more comment lines) and identifiers, nothing else: the same lines of code in the
// same order, each the same but for identifier characters, and no more lines ending in a
// backslash (which would splice the next line into a comment in every C preprocessor: GLSL,
// HLSL, OSL).
inline void same_structure(const char* what, const std::string& named, const std::string& plain) {
  auto code = [](const std::string& text, std::vector<std::string>& shapes, std::vector<std::string>& lines) {
    size_t splices = 0;
    for (const std::string& line : lines_of(text)) {
      if (!line.empty() && line.back() == '\\') ++splices;
      const size_t first = line.find_first_not_of(" \t");
      if (first != std::string::npos && line.compare(first, 2, "//") == 0) continue;  // a comment line
      shapes.push_back(shape_of(line));
      lines.push_back(line);
    }
    return splices;
  };
  std::vector<std::string> a, b, a_lines, b_lines;
  const size_t a_splices = code(named, a, a_lines), b_splices = code(plain, b, b_lines);
  if (a_splices != b_splices) fail(what, "a name ends a line with a backslash", named.substr(0, 2000));
  if (a.size() != b.size())
    fail(what, "a name changed the number of lines of code (" + std::to_string(a.size()) + " vs " +
                   std::to_string(b.size()) + ")",
         named.substr(0, 2000));
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) fail(what, "a name changed a line of code", a_lines[i] + "\n  instead of\n" + b_lines[i]);
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
