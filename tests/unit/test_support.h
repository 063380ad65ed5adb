// Helpers the tests that run the facet binary share: a scratch folder per
// process and test suite, and `facet ARGS…` run as a user runs it.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "renderers/process.h"

namespace facet::test {

// A file (or folder) name under a temporary folder of this process, e.g. scratch("cli", "a.frag").
inline std::filesystem::path scratch(const std::string& suite, const std::string& name) {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("facet-" + suite + "-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

#ifdef FACET_BIN
// The facet binary with `args`, standard input from `stdin_file` when given; output is stdout and stderr together.
inline ProcessResult facet(const std::vector<std::string>& args, const std::string& stdin_file = "") {
  std::string cmd = "'" + std::string(FACET_BIN) + "'";
  for (const auto& a : args) cmd += " '" + a + "'";
  if (!stdin_file.empty()) cmd += " < '" + stdin_file + "'";
  return run_process({"sh", "-c", cmd});
}
#endif

}  // namespace facet::test
