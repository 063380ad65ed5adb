// facet's fuzz targets share one rule: bad input may only ever be refused with
// an InputError (which names the file and the key path, as the command line
// prints it). Any other exception escaping facet is a bug the fuzzer reports,
// like a crash, a hang or a sanitizer finding: a user would have seen
// "terminate called after throwing …" instead of an error message.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

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

}  // namespace facet::fuzz
