// facet — the code generators: one material, equivalent code for each target.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "catalog/program.h"
#include "scene/scene.h"

namespace facet {

enum class Target { Glsl, Glsl450, Essl, Osl, Pov };
std::optional<Target> parse_target(const std::string& name);
const char* target_name(Target t);
const std::vector<Target>& all_targets();

struct GenerateOptions {
  Target target = Target::Glsl;
  bool library = false;        // just the functions (GLSL, OSL) / an include file (POV-Ray)
  std::optional<Scene> scene;  // OSL: its lights; POV-Ray: the whole scene. Default: default_scene()
  std::string source;          // named in the header comment
};

std::string generate(const Material& m, const GenerateOptions& options);

// ---- Parts the renderers assemble themselves.

// GLSL in pieces: the library (constants, terms, facet_reflect), the light loop
// (uniforms, facet_shade) and the standalone main.
struct GlslParts {
  std::string header, library, lights, main;
};
GlslParts glsl_parts(const MaterialProgram& p, Target dialect, const std::string& source);

// The robustness sweep's programs (facet/sweep.h): the material's functions
// under a main that evaluates the sweep grid.
std::string glsl_sweep_source(const Material& m);
std::string osl_sweep_source(const Material& m);
std::string generate_pov_sweep(const Material& m);

// How POV-Ray evaluates this material in this scene.
struct PovPlan {
  bool native = false;  // POV's own finish reproduces the model exactly
  std::string reason;   // why not, when not
  // Renders to sum for the exact image (Declare=Facet_Light=i, i < passes);
  // one render with Facet_Light=-1 is exact when passes == 1.
  int passes = 1;
};
PovPlan pov_plan(const Material& m, const Scene& s);
// Objects without a material of their own use `fallback` (may be null when every object has one).
PovPlan pov_plan(const Scene& s, const Material* fallback);
// The POV-Ray scene of a whole scene with its objects' own materials.
std::string generate_pov_scene(const Scene& s, const Material* fallback, const std::string& source);

}  // namespace facet
