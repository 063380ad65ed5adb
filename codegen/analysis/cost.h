// facet — what the generated code costs: the survey's "relative cost of the
// lighting models" (its Appendix B), measured on every target.
//
// Per material and target:
//  * GLSL: the SPIR-V instruction count of the cost frame's fragment shader
//    (renderers/harness/cost.glsl: one sphere, one point light, no loop) after
//    `glslangValidator -G --aml` and `spirv-opt -O`, and the x86 instructions
//    per pixel llvmpipe executes for its draw, counted by callgrind
//    (LP_NUM_THREADS=0 so the draw runs in the calling thread, collection on
//    around the draw only, after an untimed first draw that JIT-compiles it;
//    MESA_SHADER_CACHE_DISABLE so every process compiles alike).
//    The HLSL path: the same material printed as HLSL (--target hlsl) in the same frame
//    as a pixel shader (renderers/harness/cost.hlsl), through glslangValidator -D -V and
//    spirv-opt -O, counted alike (the glsl cell's "hlsl_spirv"). The WGSL path's size:
//    the bytes of --target wgsl --library without comment and blank lines ("wgsl_bytes").
//  * OSL: the ops of the shader Blender's OSL compiler makes (.oso), and Cycles'
//    render time per pixel and sample, by difference of two sample counts (the
//    per-render set-up cancels), min over interleaved repeats, in CPU time.
//  * POV-Ray: the `#declare … = function` count of the generated scene
//    (`native` for a native finish) and the trace time per pixel POV-Ray reports
//    (+WT1), min over interleaved repeats.
// Every figure is also given relative to the Lambert material's. Timings are
// noisy on a shared machine and never asserted; the counts are deterministic.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "renderers/opengl.h"

namespace facet {

// ---- The rows: one per material, a cell per target (`facet cost --json` prints them and `facet docs` reads them).

// One target's figures, under the keys `facet cost --json` prints: a number, a
// boolean, or null where not measured (timings with --no-timings); a figure the
// format does not name is kept as it is.
struct CostCell {
  std::string error;  // why the target was not measured; empty when it was
  nlohmann::json figures = nlohmann::json::object();
  double number(const std::string& key) const;  // 0 when absent or null
  bool flag(const std::string& key) const;      // false when absent
};

struct CostRow {
  std::string name;      // the material's name
  std::string material;  // its file, or the model's name for model_materials()
  std::string diffuse, specular;  // model names, "" for none
  std::vector<std::string> layers;  // the layer models over them, the lowest first
  std::map<std::string, CostCell> cells;  // by target: a renderer's name ("glsl"), see cost_format()
  CostCell& cell(const std::string& target) { return cells[target]; }
  const CostCell& cell(const std::string& target) const;  // an empty cell when the row has none
  bool ok() const;
};

// The figures the agreed format names for a target, each with how the pages print it.
enum class CostFigureKind { Count, Number, Ratio, Flag, CountOrNull };
struct CostFigureDef {
  std::string key;    // as in the file, e.g. "ns_per_pixel"
  std::string label;  // as the pages print it, e.g. "ns / pixel"
  CostFigureKind kind;
};
struct CostTargetFormat {
  std::string target;                 // the renderer whose target it measures
  std::vector<CostFigureDef> figures;  // every cell has these (or an error), in the order shown
  std::string timed, relative;        // the figure given relative to the baseline, and that ratio's key
};
// glsl, osl, pov: the registry's renderers that have a cost, in the registry's order.
const std::vector<CostTargetFormat>& cost_format();

// What the whole table shares: the per-pixel costs of a frame that shades
// nothing, and the tools that measured.
struct CostBaselines {
  double callgrind_empty_per_pixel = 0;  // the cost frame with facet_reflect() = 0
  int spirv_empty = 0;
  int hlsl_spirv_empty = 0;  // the same frame as an HLSL pixel shader
  double cycles_emission_ns_per_pixel = 0;  // a constant-emission OSL shader on the same sphere
  std::string gl_renderer;   // GL_RENDERER, GL_VERSION
  std::string blender, osl;  // versions
  std::string povray, glslang, spirv_tools, valgrind;
};

// valgrind cannot run a binary built with AddressSanitizer, so a sanitizer
// build (FACET_SANITIZE) measures everything but llvmpipe's instruction counts;
// the release build measures those.
bool callgrind_available();

struct CostOptions {
  bool timings = true;    // Cycles and POV-Ray render times; off: only the deterministic counts
  bool callgrind = callgrind_available();  // llvmpipe instructions per pixel under valgrind
  int callgrind_size = 256;  // the draw's width and height
  int cycles_size = 128;
  int cycles_samples = 64;   // the extra samples whose time is measured (1 + this against 1)
  int cycles_repeats = 7;  // interleaved rounds of Cycles renders; each time is the least
  int pov_size = 384;
  int repeats = 5;        // interleaved rounds of POV-Ray renders; each time is the least
  int jobs = 2;           // processes at once (valgrind runs, renders)
  std::string python;     // bpy's Python; empty: default_python()
  std::string facet;      // this facet binary (its draw-shaders command runs under valgrind); empty: the built one
  std::string workdir;    // empty: a temporary folder
};

using CostProgress = std::function<void(const std::string&)>;

// Every figure of every material, target after target in the registry's order.
// The baseline is the first material that is cost_baseline_model()'s lobe alone,
// named after it ("lambert"); without one, that lobe at its defaults is measured
// first as such a row. A tool that cannot run leaves its error in every row it concerns.
std::vector<CostRow> measure_costs(const std::vector<Material>& materials, const CostOptions& options,
                                   const CostProgress& progress = {}, CostBaselines* baselines = nullptr);

// {"baseline": "lambert", "rows": [...], "frame": {…}, "tools": {…}} (the format
// `facet cost --json` prints and `facet docs` reads), and the same rows as a
// plain-text and a Markdown table.
nlohmann::json costs_json(const std::vector<CostRow>& rows, const CostBaselines& baselines);
std::string costs_table(const std::vector<CostRow>& rows, const CostBaselines& baselines);
std::string costs_markdown(const std::vector<CostRow>& rows, const CostBaselines& baselines,
                           const CostOptions& options, double wall_seconds);
// The rows as `facet docs` shows them, read from `facet cost --json`'s output or
// made from a measurement; "frame" (what the measuring frame alone costs) and
// "tools" (their versions) are shown as they are.
struct CostTable {
  std::string source;  // the file (or what measured), for the pages
  std::string baseline;
  std::vector<CostRow> rows;
  nlohmann::json frame = nlohmann::json::object(), tools = nlohmann::json::object();
  const CostRow* find(const std::string& name) const;
};
CostTable cost_table(const std::vector<CostRow>& rows, const CostBaselines& baselines, const std::string& source);
// Checks `doc` (what `facet cost --json` prints); every problem names `file` and
// the key path. Throws InputError. Figures the agreed format does not name are
// kept, so a newer cost command still documents.
CostTable parse_cost_rows(const nlohmann::json& doc, const std::string& file);
CostTable load_cost_rows(const std::string& path);

// The deterministic figures of docs/cost.md (SPIR-V, callgrind, OSL ops, POV-Ray
// functions) against `rows`: one line per difference, empty when current.
std::vector<std::string> stale_costs(const std::string& markdown, const std::vector<CostRow>& rows);

// ---- The pieces, for the benchmarks in tests/bench.

// The cost frame (renderers/harness/cost_raycast.glsl and cost.glsl) under `library`:
// GLSL that defines material_ambient, material_emission, facet_tangent(n) and
// facet_reflect(n, l, v, t).
std::string cost_frame_source(const std::string& library);
// Its uniforms and facet_camera_hit(dir, p, n), for a main of another generator's.
std::string cost_raycast_source();
// facet's generated library under the cost frame.
std::string cost_fragment_source(const Material& m);
// The same frame as an HLSL pixel shader (renderers/harness/cost.hlsl) under an HLSL
// library, and facet's generated HLSL library under it: the HLSL path's SPIR-V count.
std::string hlsl_cost_frame_source(const std::string& library);
std::string hlsl_cost_fragment_source(const Material& m);
// The frame's uniforms: the built-in scene "single" at width × height.
std::vector<std::pair<std::string, std::vector<double>>> cost_frame_uniforms(int width, int height);

// SPIR-V instructions inside function bodies after glslangValidator -G --aml
// (OpenGL SPIR-V, locations assigned) and spirv-opt -O; counted: every
// instruction but OpFunction, OpFunctionParameter, OpFunctionEnd, OpLabel,
// OpVariable, OpLine, OpNoLine, OpSelectionMerge, OpLoopMerge, OpPhi, OpBranch,
// OpReturn, OpReturnValue, OpUnreachable and OpSwitch (structure, not work: the
// only switches are the one-case switches on a constant in which spirv-opt's
// inliner wraps an early return).
struct SpirvCount {
  int instructions = 0;
  std::string error;
  std::string disassembly;  // of the optimized module
  std::string module;       // the compiler's module (SPIR-V, before spirv-opt), a file in the workdir
};
SpirvCount spirv_instructions(const std::string& glsl, const std::string& workdir, const std::string& name);
// The same count for HLSL: glslangValidator -D -V -S frag -e main (Vulkan SPIR-V), spirv-opt -O.
SpirvCount hlsl_spirv_instructions(const std::string& hlsl, const std::string& workdir, const std::string& name);

// x86 instructions per pixel llvmpipe executes for each shader's draw, under
// callgrind, in options.jobs valgrind processes; `error` set for a shader that failed.
struct CallgrindCount {
  double per_pixel = 0;
  std::string error;
};
std::vector<CallgrindCount> callgrind_draws(const std::vector<ShaderDraw>& shaders, int width, int height,
                                            const CostOptions& options, const std::string& workdir);

// The hidden `facet draw-shaders JOB.json` (what callgrind_draws runs under
// valgrind): draws the job's shaders with GlRenderer::draw, callgrind's
// collection on around each measured draw and its counts dumped per shader.
int run_draw_job(const std::string& job_path);

}  // namespace facet
