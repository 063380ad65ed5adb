// facet — running the external tools (povray, Blender's Python) and capturing what they say.
#pragma once

#include <string>
#include <vector>

namespace facet {

struct ProcessResult {
  int exit_code = -1;   // -1: could not start; 128 + n: killed by signal n
  std::string output;   // stdout and stderr together
  double seconds = 0;
};

// Runs argv[0] (searched on PATH) in `cwd` with extra environment entries "K=V".
ProcessResult run_process(const std::vector<std::string>& argv, const std::string& cwd = "",
                          const std::vector<std::string>& env = {});
// The full path of a program on PATH, or "".
std::string find_program(const std::string& name);

}  // namespace facet
