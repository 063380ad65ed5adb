// What the generated code costs (analysis/cost.h): counts from the compilers,
// callgrind's instruction counts of llvmpipe's draws, render times of Cycles and
// POV-Ray. Each tool runs as few times as it can: one valgrind process per core
// for all the shaders, one Blender process for all the OSL, and the timings
// interleaved so drift touches every material alike.
#include "analysis/cost.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <valgrind/callgrind.h>

#include "catalog/program.h"
#include "core/io.h"
#include "core/parallel.h"
#include "renderers/harness.h"
#include "renderers/process.h"
#include "scene/scene.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------- the GLSL cost frame

std::string cost_raycast_source() { return render_harness("cost_raycast.glsl"); }

std::string cost_frame_source(const std::string& library) {
  return "#version 330 core\n" + library + cost_raycast_source() + render_harness("cost.glsl");
}

std::string cost_fragment_source(const Material& m) {
  GlslParts parts = glsl_parts(compile(m), Target::Glsl, m.source.empty() ? "the catalog" : m.source);
  return cost_frame_source(parts.header + parts.library);
}

std::string hlsl_cost_frame_source(const std::string& library) { return library + render_harness("cost.hlsl"); }

std::string hlsl_cost_fragment_source(const Material& m) {
  HlslParts parts = hlsl_parts(compile(m), m.source.empty() ? "the catalog" : m.source);
  return hlsl_cost_frame_source(parts.header + parts.library);
}

std::vector<std::pair<std::string, std::vector<double>>> cost_frame_uniforms(int width, int height) {
  const Scene s = default_scene();
  const Camera::Basis b = s.camera.basis();
  const Object& sphere = s.objects.at(0);
  const Light& light = s.lights.at(0);
  auto v3 = [](const Vec3& v) { return std::vector<double>{v.x, v.y, v.z}; };
  return {{"facet_resolution", {double(width), double(height)}},
          {"facet_camera_position", v3(s.camera.position)},
          {"facet_camera_forward", v3(b.forward)},
          {"facet_camera_right", v3(b.right)},
          {"facet_camera_up", v3(b.up)},
          {"facet_camera_tan", {b.tan_half * width / height, b.tan_half}},
          {"facet_sphere", {sphere.center.x, sphere.center.y, sphere.center.z, sphere.radius}},
          {"facet_light_position", v3(light.position)},
          {"facet_light_color", {light.color[0], light.color[1], light.color[2]}},
          {"facet_ambient", {s.ambient[0], s.ambient[1], s.ambient[2]}}};
}

namespace {

// The frame shading nothing: what every material's figures include.
const char* kEmptyLibrary = R"(
const vec3 material_ambient = vec3(0.0);
const vec3 material_emission = vec3(0.0);
vec3 facet_tangent(vec3 n) { return n; }
vec3 facet_reflect(vec3 n, vec3 l, vec3 v, vec3 t) { return n + l + v; }
)";

// The same in HLSL.
const char* kEmptyHlslLibrary = R"(
static const float3 material_ambient = float3(0.0, 0.0, 0.0);
static const float3 material_emission = float3(0.0, 0.0, 0.0);
float3 facet_tangent(float3 n) { return n; }
float3 facet_reflect(float3 n, float3 l, float3 v, float3 t) { return n + l + v; }
)";

// A constant-emission shader on the same sphere: what Cycles spends on a sample
// whatever the shader.
const char* kEmissionOsl = R"(shader facet_cost_emission(output closure color Out = 0)
{
    Out = color(0.5) * emission();
}
)";

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

// The first line of a tool's answer to `--version` that names `what` (POV-Ray
// complains about its configuration file first).
std::string tool_version(const std::vector<std::string>& argv, const std::string& what) {
  ProcessResult r = run_process(argv);
  if (r.exit_code < 0) return "not found";
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(what) == std::string::npos) continue;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    return line;
  }
  return first_line(r.output);
}

}  // namespace

// ---------------------------------------------------------------- SPIR-V

namespace {

bool structural(const std::string& op) {
  static const char* const kStructure[] = {"OpFunction", "OpFunctionParameter", "OpFunctionEnd", "OpLabel",
                                          "OpVariable", "OpLine", "OpNoLine", "OpSelectionMerge",
                                          "OpLoopMerge", "OpPhi", "OpBranch", "OpReturn",
                                          "OpReturnValue", "OpUnreachable", "OpSwitch"};
  for (const char* s : kStructure)
    if (op == s) return true;
  return false;
}

int count_spirv(const std::string& disassembly) {
  std::istringstream in(disassembly);
  bool inside = false;
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string op;
    for (std::string w; words >> w;)
      if (w.rfind("Op", 0) == 0) {
        op = w;
        break;
      }
    if (op.empty()) continue;
    if (op == "OpFunction") inside = true;
    if (inside && !structural(op)) ++n;
    if (op == "OpFunctionEnd") inside = false;
  }
  return n;
}

}  // namespace

namespace {

// `source` compiled by `compile` (the compiler's arguments before "-o SPV SOURCE"), then
// spirv-opt -O and counted.
SpirvCount spirv_count(const std::string& source, const std::string& workdir, const std::string& name,
                       const std::string& extension, std::vector<std::string> compile) {
  SpirvCount out;
  fs::create_directories(workdir);
  const fs::path base = fs::path(workdir) / identifier(name);
  const std::string file = base.string() + extension, spv = base.string() + ".spv", opt = base.string() + ".opt.spv",
                    dis = base.string() + ".opt.spvasm";
  write_file_atomic(file, source);
  auto step = [&](const std::vector<std::string>& argv) {
    ProcessResult r = run_process(argv);
    if (r.exit_code != 0) out.error = fmt::format("{} exited with {}: {}", argv[0], r.exit_code, r.output);
    return r.exit_code == 0;
  };
  compile.insert(compile.end(), {"-o", spv, file});
  out.module = spv;
  if (!step(compile) || !step({"spirv-opt", "-O", spv, "-o", opt}) || !step({"spirv-dis", opt, "-o", dis}))
    return out;
  out.disassembly = read_file(dis);
  out.instructions = count_spirv(out.disassembly);
  return out;
}

}  // namespace

SpirvCount spirv_instructions(const std::string& glsl, const std::string& workdir, const std::string& name) {
  return spirv_count(glsl, workdir, name, ".frag", {"glslangValidator", "-G", "--aml"});
}

SpirvCount hlsl_spirv_instructions(const std::string& hlsl, const std::string& workdir, const std::string& name) {
  return spirv_count(hlsl, workdir, name, ".hlsl", {"glslangValidator", "-D", "-V", "-S", "frag", "-e", "main"});
}

// ---------------------------------------------------------------- callgrind

int run_draw_job(const std::string& job_path) {
  json job = json::parse(read_file(job_path));
  std::vector<ShaderDraw> shaders;
  for (const auto& s : job["shaders"]) {
    ShaderDraw d;
    d.name = s["name"];
    d.fragment_source = read_file(s["fragment"]);
    for (const auto& [name, values] : s["uniforms"].items()) d.uniforms.push_back({name, values.get<std::vector<double>>()});
    shaders.push_back(d);
  }
  GlRenderer gl;
  std::vector<std::string> dumps;
  for (size_t i = 0; i < shaders.size(); ++i) dumps.push_back(fmt::format("facet-shader-{}", i));
  // valgrind starts without instrumentation (--instr-atstart=no), which runs
  // start-up and the JIT draws several times faster; it is switched on before
  // the first measured draw. Collection is off at start (--collect-atstart=no)
  // and on only around each measured draw; each shader's count is dumped under
  // its own name.
  auto around = [&](size_t i, bool before) {
    if (before && i == 0) CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_TOGGLE_COLLECT;
    if (!before) CALLGRIND_DUMP_STATS_AT(dumps[i].c_str());
  };
  std::vector<RenderOutcome> drawn = gl.draw(shaders, job["width"], job["height"], around);
  json result = {{"gl_renderer", gl.description()}, {"shaders", json::array()}};
  for (size_t i = 0; i < shaders.size(); ++i)
    result["shaders"].push_back({{"name", shaders[i].name}, {"dump", dumps[i]}, {"ok", drawn[i].ok}, {"error", drawn[i].error}});
  write_file_atomic(job_path + ".result.json", result.dump(1));
  return gl.ok() ? 0 : 1;
}

namespace {

std::string facet_binary(const CostOptions& o) {
  if (!o.facet.empty()) return o.facet;
#ifdef FACET_BIN
  if (fs::exists(FACET_BIN)) return FACET_BIN;
#endif
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return !ec && self.filename() == "facet" ? self.string() : "facet";
}

// Every dump callgrind wrote for `prefix`: the client request's name → instructions.
std::map<std::string, double> read_dumps(const fs::path& dir, const std::string& prefix) {
  std::map<std::string, double> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().rfind(prefix, 0) != 0) continue;
    std::ifstream in(e.path());
    std::string trigger;
    double total = -1;
    for (std::string line; std::getline(in, line);) {
      const std::string request = "desc: Trigger: Client Request: ";
      if (line.rfind(request, 0) == 0) trigger = line.substr(request.size());
      if (line.rfind("summary: ", 0) == 0) total = std::stod(line.substr(9));
      if (line.rfind("totals: ", 0) == 0 && total < 0) total = std::stod(line.substr(8));
    }
    if (!trigger.empty() && total >= 0) out[trigger] = total;
  }
  return out;
}

// One valgrind process drawing `indices` of `shaders`.
void callgrind_chunk(const std::vector<ShaderDraw>& shaders, const std::vector<size_t>& indices, int width,
                     int height, const std::string& facet, const fs::path& dir, int chunk,
                     std::vector<CallgrindCount>& out) {
  json job = {{"width", width}, {"height", height}, {"shaders", json::array()}};
  for (size_t i : indices) {
    std::string frag = (dir / fmt::format("{}_{:03}.frag", identifier(shaders[i].name), i)).string();
    write_file_atomic(frag, shaders[i].fragment_source);
    json uniforms = json::object();
    for (const auto& [name, values] : shaders[i].uniforms) uniforms[name] = values;
    job["shaders"].push_back({{"name", shaders[i].name}, {"fragment", frag}, {"uniforms", uniforms}});
  }
  const std::string prefix = fmt::format("callgrind.{}.out", chunk);
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(prefix, 0) == 0) fs::remove(e.path());
  const fs::path job_file = dir / fmt::format("draw_job_{}.json", chunk);
  write_file_atomic(job_file.string(), job.dump(1));
  fs::remove(job_file.string() + ".result.json");
  ProcessResult r = run_process({"valgrind", "--tool=callgrind", "--instr-atstart=no", "--collect-atstart=no",
                                 "--callgrind-out-file=" + (dir / prefix).string(), facet, "draw-shaders",
                                 job_file.string()},
                                dir.string(), {"LP_NUM_THREADS=0", "MESA_SHADER_CACHE_DISABLE=true"});
  json result;
  try {
    result = json::parse(read_file(job_file.string() + ".result.json"));
  } catch (const std::exception&) {
    for (size_t i : indices)
      out[i].error = fmt::format("valgrind ({} draw-shaders) exited with {} and wrote no result:\n{}", facet,
                                 r.exit_code, r.output.substr(r.output.size() > 4000 ? r.output.size() - 4000 : 0));
    return;
  }
  std::map<std::string, double> counts = read_dumps(dir, prefix);
  for (size_t k = 0; k < indices.size(); ++k) {
    const json& s = result["shaders"].at(k);
    CallgrindCount& c = out[indices[k]];
    auto it = counts.find(s["dump"].get<std::string>());
    if (!s["ok"].get<bool>()) c.error = s["error"];
    else if (it == counts.end()) c.error = "callgrind wrote no count for this draw:\n" + r.output;
    else c.per_pixel = it->second / (double(width) * height);
  }
}

}  // namespace

std::vector<CallgrindCount> callgrind_draws(const std::vector<ShaderDraw>& shaders, int width, int height,
                                            const CostOptions& options, const std::string& workdir) {
  std::vector<CallgrindCount> out(shaders.size());
  if (find_program("valgrind").empty()) {
    for (auto& c : out) c.error = "valgrind is not installed (Debian package valgrind)";
    return out;
  }
  fs::create_directories(workdir);
  const fs::path dir = fs::absolute(workdir);
  const std::string facet = facet_binary(options);
  // Round-robin over the processes: start-up and the JIT under valgrind dominate,
  // and they are paid once per process.
  const size_t jobs = std::max<size_t>(1, std::min<size_t>(size_t(std::max(options.jobs, 1)), shaders.size()));
  std::vector<std::vector<size_t>> chunks(jobs);
  for (size_t i = 0; i < shaders.size(); ++i) chunks[i % jobs].push_back(i);
  parallel_for(jobs, unsigned(jobs), [&](size_t k) {
    callgrind_chunk(shaders, chunks[k], width, height, facet, dir, int(k), out);
  });
  return out;
}


// ---------------------------------------------------------------- Cycles (OSL)

namespace {

struct OslCost {
  std::string error;
  int instructions = 0;
  double ns_per_pixel = 0;  // per pixel and sample; 0 when not timed
};

struct OslFigures {
  std::vector<OslCost> rows;
  double emission_ns_per_pixel = 0;
  std::string blender, osl;
};

// One Blender process: every material's OSL for the scene "single", then a
// constant-emission shader, the baseline.
OslFigures cycles_costs(const std::vector<Material>& ms, const CostOptions& o, const fs::path& dir) {
  OslFigures out;
  out.rows.resize(ms.size());
  fs::create_directories(dir);
  const fs::path script = dir / "cycles_cost.py";
  write_file_atomic(script.string(), embedded_harness().at("cycles_cost.py"));
  write_file_atomic((dir / "cycles_render.py").string(), embedded_harness().at("cycles_render.py"));
  json items = json::array();
  for (size_t i = 0; i < ms.size(); ++i) {
    GenerateOptions g;
    g.target = Target::Osl;
    g.source = ms[i].source;
    const std::string path = (dir / fmt::format("{}_{:03}.osl", identifier(ms[i].name), i)).string();
    write_file_atomic(path, generate(ms[i], g));
    items.push_back({{"name", ms[i].name}, {"osl", path}});
  }
  const std::string emission = (dir / "emission.osl").string();
  write_file_atomic(emission, kEmissionOsl);
  items.push_back({{"name", "(emission)"}, {"osl", emission}});
  json job = {{"width", o.cycles_size},  {"height", o.cycles_size},      {"scene", to_json(default_scene())},
              {"samples", o.cycles_samples}, {"repeats", o.cycles_repeats}, {"time", o.timings},
              {"items", items}};
  const fs::path job_file = dir / "cost_job.json";
  write_file_atomic(job_file.string(), job.dump(1));
  fs::remove(job_file.string() + ".result.json");
  const std::string python = o.python.empty() ? default_python() : o.python;
  ProcessResult r = run_process({python, script.string(), job_file.string()}, dir.string());
  json result;
  try {
    result = json::parse(read_file(job_file.string() + ".result.json"));
  } catch (const std::exception&) {
    for (auto& c : out.rows)
      c.error = r.exit_code < 0 ? fmt::format("cannot run {}: {}", python, r.output)
                                : fmt::format("Blender ({} {}) exited with {} and wrote no result:\n{}", python,
                                              script.string(), r.exit_code, r.output);
    return out;
  }
  out.blender = result.value("blender", "");
  out.osl = result.value("osl", "");
  const json& ri = result["items"];
  for (size_t i = 0; i < ms.size(); ++i) {
    OslCost& c = out.rows[i];
    if (!ri[i].value("ok", false)) {
      c.error = ri[i].value("error", std::string("Blender reported a failure"));
      continue;
    }
    c.instructions = ri[i]["instructions"];
    c.ns_per_pixel = ri[i]["ns_per_pixel"];
  }
  const json& base = ri[ms.size()];
  if (base.value("ok", false)) out.emission_ns_per_pixel = base["ns_per_pixel"];
  return out;
}

// ---------------------------------------------------------------- POV-Ray

struct PovCost {
  std::string error;
  bool native = false;      // POV-Ray's own finish, no functions
  int functions = 0;        // #declare … = function in the generated scene
  double ns_per_pixel = 0;  // 0 when not timed
};

int count_pov_functions(const std::string& scene) {
  static const std::regex declaration(R"(#declare\s+\w+\s*=\s*function\b)");
  return int(std::distance(std::sregex_iterator(scene.begin(), scene.end(), declaration), std::sregex_iterator()));
}

// The trace's CPU time POV-Ray reports ("Trace Time: … using 1 thread(s) with
// X CPU-seconds total"): less disturbed than wall time by other processes.
double trace_cpu_seconds(const std::string& log) {
  static const std::regex trace(R"(Trace Time:[^\n]*\n\s*using \d+ thread\(s\) with ([0-9.]+) CPU-seconds)");
  std::smatch m;
  return std::regex_search(log, m, trace) ? std::stod(m[1]) : -1;
}

void pov_counts(const std::vector<Material>& ms, const fs::path& dir, std::vector<PovCost>& out) {
  fs::create_directories(dir);
  const Scene scene = default_scene();
  for (size_t i = 0; i < ms.size(); ++i) {
    GenerateOptions g;
    g.target = Target::Pov;
    g.source = ms[i].source;
    const std::string code = generate(ms[i], g);
    write_file_atomic((dir / fmt::format("{}_{:03}.pov", identifier(ms[i].name), i)).string(), code);
    out[i].native = pov_plan(ms[i], scene).native;
    out[i].functions = count_pov_functions(code);
  }
}

// Rounds of one render per material, the order reversed every other round.
void pov_timings(const std::vector<Material>& ms, const CostOptions& o, const fs::path& dir,
                 std::vector<PovCost>& out) {
  std::vector<double> best(ms.size(), -1);
  for (int round = 0; round < o.repeats; ++round) {
    for (size_t k = 0; k < ms.size(); ++k) {
      const size_t i = round % 2 ? ms.size() - 1 - k : k;
      if (!out[i].error.empty()) continue;
      const std::string file = fmt::format("{}_{:03}.pov", identifier(ms[i].name), i);
      ProcessResult r = run_povray({"+I" + file, "-F", fmt::format("+W{}", o.pov_size), fmt::format("+H{}", o.pov_size),
                                    "-A", "+WT1", "-D", "-GR", "File_Gamma=1.0"},
                                   dir.string());
      double s = trace_cpu_seconds(r.output);
      if (r.exit_code != 0 || s < 0) {
        out[i].error = fmt::format("povray exited with {} and reported no trace time:\n{}", r.exit_code, r.output);
        continue;
      }
      best[i] = best[i] < 0 ? s : std::min(best[i], s);
    }
  }
  for (size_t i = 0; i < ms.size(); ++i)
    if (out[i].error.empty()) out[i].ns_per_pixel = best[i] / (double(o.pov_size) * o.pov_size) * 1e9;
}

// ---------------------------------------------------------------- the targets

json or_null(double x) { return x > 0 ? json(x) : json(nullptr); }

// x − frame: the shading alone, without what the frame (or Cycles' own path)
// costs; absent when either was not measured. Timings may come out a little below
// the frame's by noise, so the difference keeps its sign.
std::optional<double> shading(double x, double frame) {
  if (x > 0 && frame > 0) return x - frame;
  return std::nullopt;
}
json or_null(const std::optional<double>& x) { return x ? json(*x) : json(nullptr); }

// The WGSL path's size: the bytes of `facet generate --target wgsl --library` without its
// comment and blank lines, what a WebGPU page ships to createShaderModule for the material.
size_t wgsl_code_bytes(const Material& m) {
  GenerateOptions o;
  o.target = Target::Wgsl;
  o.library = true;
  std::istringstream in(generate(m, o));
  size_t bytes = 0;
  for (std::string line; std::getline(in, line);) {
    size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line.compare(first, 2, "//") != 0) bytes += line.size() + 1;
  }
  return bytes;
}

// What one target's measurement works on; it fills that target's cell of every row.
struct CostRun {
  const std::vector<Material>& ms;
  const CostOptions& options;
  const fs::path& dir;
  const std::function<void(const std::string&)>& say;
};

// GLSL: the SPIR-V counts (compilers only, seconds), then llvmpipe's draws under callgrind on every core.
void measure_glsl(const CostRun& run, std::vector<CostRow>& rows, CostBaselines& base) {
  const auto& ms = run.ms;
  const CostOptions& options = run.options;
  run.say(fmt::format("GLSL and HLSL: SPIR-V of {} shaders each (glslangValidator, spirv-opt -O)", ms.size() + 1));
  std::vector<ShaderDraw> draws;
  const auto uniforms = cost_frame_uniforms(options.callgrind_size, options.callgrind_size);
  for (size_t i = 0; i < ms.size(); ++i) {
    ShaderDraw d{ms[i].name, cost_fragment_source(ms[i]), uniforms};
    SpirvCount s = spirv_instructions(d.fragment_source, (run.dir / "glsl").string(), fmt::format("{}_{:03}", ms[i].name, i));
    // The HLSL path: the same library printed as HLSL, in the same frame as a pixel shader.
    SpirvCount h = hlsl_spirv_instructions(hlsl_cost_fragment_source(ms[i]), (run.dir / "hlsl").string(),
                                           fmt::format("{}_{:03}", ms[i].name, i));
    rows[i].cell("glsl").figures["spirv"] = s.instructions;
    rows[i].cell("glsl").figures["hlsl_spirv"] = h.instructions;
    rows[i].cell("glsl").figures["wgsl_bytes"] = static_cast<double>(wgsl_code_bytes(ms[i]));
    rows[i].cell("glsl").error = s.error.empty() ? h.error : s.error;
    draws.push_back(d);
  }
  draws.push_back({"(empty frame)", cost_frame_source(kEmptyLibrary), uniforms});
  base.spirv_empty = spirv_instructions(draws.back().fragment_source, (run.dir / "glsl").string(), "empty").instructions;
  base.hlsl_spirv_empty =
      hlsl_spirv_instructions(hlsl_cost_frame_source(kEmptyHlslLibrary), (run.dir / "hlsl").string(), "empty").instructions;
  std::vector<CallgrindCount> counts(draws.size());
  if (options.callgrind) {
    run.say(fmt::format("GLSL: llvmpipe draws of {} shaders under callgrind, {} valgrind processes", draws.size(),
                        options.jobs));
    counts = callgrind_draws(draws, options.callgrind_size, options.callgrind_size, options, (run.dir / "callgrind").string());
    base.callgrind_empty_per_pixel = counts.back().per_pixel;
  }
  for (size_t i = 0; i < ms.size(); ++i) {
    CostCell& c = rows[i].cell("glsl");
    if (!counts[i].error.empty() && c.error.empty()) c.error = counts[i].error;
    c.figures["callgrind_per_pixel"] = or_null(counts[i].per_pixel);
    c.figures["callgrind_shading_per_pixel"] = or_null(shading(counts[i].per_pixel, base.callgrind_empty_per_pixel));
  }
  base.glslang = tool_version({"glslangValidator", "--version"}, "Glslang");
  base.spirv_tools = tool_version({"spirv-opt", "--version"}, "SPIRV-Tools");
  if (options.callgrind) base.valgrind = tool_version({"valgrind", "--version"}, "valgrind");
  GlRenderer gl;
  base.gl_renderer = gl.ok() ? gl.description() : gl.error();
}

// OSL: one Blender process compiles (and, with timings, times) every shader and the emission baseline.
void measure_osl(const CostRun& run, std::vector<CostRow>& rows, CostBaselines& base) {
  run.say(run.options.timings ? "OSL: Blender compiles and times every shader in Cycles"
                              : "OSL: Blender compiles every shader");
  OslFigures osl = cycles_costs(run.ms, run.options, run.dir / "osl");
  base.cycles_emission_ns_per_pixel = osl.emission_ns_per_pixel;
  base.blender = osl.blender;
  base.osl = osl.osl;
  for (size_t i = 0; i < run.ms.size(); ++i) {
    CostCell& c = rows[i].cell("osl");
    const OslCost& o = osl.rows[i];
    c.error = o.error;
    c.figures["instructions"] = o.instructions;
    c.figures["ns_per_pixel"] = or_null(o.ns_per_pixel);
    c.figures["shading_ns_per_pixel"] = or_null(shading(o.ns_per_pixel, base.cycles_emission_ns_per_pixel));
  }
}

// POV-Ray: the generated scenes' function counts, then (with timings) their traces, one at a time.
void measure_pov(const CostRun& run, std::vector<CostRow>& rows, CostBaselines& base) {
  std::vector<PovCost> pov(run.ms.size());
  pov_counts(run.ms, run.dir / "pov", pov);
  if (run.options.timings) {
    run.say("POV-Ray: tracing every scene");
    pov_timings(run.ms, run.options, run.dir / "pov", pov);
  }
  for (size_t i = 0; i < run.ms.size(); ++i) {
    CostCell& c = rows[i].cell("pov");
    c.error = pov[i].error;
    c.figures["native"] = pov[i].native;
    c.figures["functions"] = pov[i].native ? json(nullptr) : json(pov[i].functions);
    c.figures["ns_per_pixel"] = or_null(pov[i].ns_per_pixel);
  }
  base.povray = tool_version({"povray", "--version"}, "POV-Ray");
}

using CostMeasure = void (*)(const CostRun&, std::vector<CostRow>&, CostBaselines&);

// How each target of cost_format() is measured, by its renderer's name.
CostMeasure cost_measure(const std::string& target) {
  static const std::map<std::string, CostMeasure> measures = {
      {"glsl", measure_glsl}, {"osl", measure_osl}, {"pov", measure_pov}};
  auto it = measures.find(target);
  return it == measures.end() ? nullptr : it->second;
}

// ---------------------------------------------------------------- the table

// The baseline: the baseline model's lobe alone, in a material named after it.
bool is_baseline(const Material& m) {
  const ModelDef& base = cost_baseline_model();
  return m.diffuse && !m.specular && m.diffuse->def == &base && m.name == base.name;
}

double ratio(double x, double base) { return base > 0 && x > 0 ? x / base : 0; }

std::vector<CostRow> named_rows(const std::vector<Material>& ms) {
  std::vector<CostRow> rows(ms.size());
  for (size_t i = 0; i < ms.size(); ++i) {
    rows[i].name = ms[i].name;
    rows[i].material = ms[i].source.empty() ? ms[i].name : ms[i].source;
    if (ms[i].diffuse) rows[i].diffuse = ms[i].diffuse->def->name;
    if (ms[i].specular) rows[i].specular = ms[i].specular->def->name;
    for (const auto& layer : ms[i].layers) rows[i].layers.push_back(layer.def->name);
  }
  return rows;
}

}  // namespace

std::vector<CostRow> measure_costs(const std::vector<Material>& materials, const CostOptions& options,
                                   const CostProgress& progress, CostBaselines* baselines) {
  // The cost frame shades a sphere without texture coordinates.
  for (const Material& m : materials)
    require_no_images(m, "which facet cost's frame cannot give (it has no texture coordinates): it measures "
                         "materials of numbers");
  const std::function<void(const std::string&)> say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  std::vector<Material> ms = materials;
  if (std::none_of(ms.begin(), ms.end(), is_baseline)) {
    const ModelDef& base = cost_baseline_model();
    ms.insert(ms.begin(), lobe_material(default_spec(base), base.name));
  }
  const fs::path dir = fs::absolute(options.workdir.empty() ? (fs::path(private_work_folder()) / "cost").string()
                                                            : options.workdir);
  fs::create_directories(dir);
  std::vector<CostRow> rows = named_rows(ms);
  CostBaselines base;
  // The targets one after another: the timings must not share the cores.
  const CostRun run{ms, options, dir, say};
  for (const auto& format : cost_format())
    if (CostMeasure measure = cost_measure(format.target)) measure(run, rows, base);
  // Relative to the baseline.
  const CostRow& baseline = rows[size_t(std::find_if(ms.begin(), ms.end(), is_baseline) - ms.begin())];
  for (const auto& format : cost_format()) {
    const double b = baseline.cell(format.target).number(format.timed);
    for (auto& r : rows)
      r.cell(format.target).figures[format.relative] = or_null(ratio(r.cell(format.target).number(format.timed), b));
  }
  if (baselines) *baselines = base;
  return rows;
}

// ---------------------------------------------------------------- output

namespace {

std::string signed_number(const std::optional<double>& x, int decimals) {
  return x ? fmt::format("{:.{}f}", *x, decimals) : "–";
}

std::string lobes(const CostRow& r) {
  std::string s = !r.diffuse.empty() && !r.specular.empty() ? r.diffuse + " + " + r.specular
                                                            : r.diffuse.empty() ? r.specular : r.diffuse;
  for (const auto& layer : r.layers) s += " / " + layer;  // each layer over what is left of it
  return s;
}

std::string number(double x, int decimals) { return x > 0 ? fmt::format("{:.{}f}", x, decimals) : "–"; }
std::string times(double x) { return x > 0 ? fmt::format("{:.2f}", x) : "–"; }
std::string ns(double x) { return x > 0 ? fmt::format("{:.{}f}", x, x >= 100 ? 0 : 1) : "–"; }
std::string count(const CostCell& c, const char* key) { return fmt::format("{}", (long long)c.number(key)); }

std::string pov_kind(const CostCell& p) {
  if (!p.error.empty()) return "error";
  return p.flag("native") ? "native" : fmt::format("{} functions", count(p, "functions"));
}

}  // namespace

std::string costs_table(const std::vector<CostRow>& rows, const CostBaselines& b) {
  std::string s = fmt::format("{:<20} {:<16} {:>6} {:>6} {:>6} {:>10} {:>6} {:>7} {:>9} {:>6} {:>14} {:>9} {:>6}\n",
                              "material", "lobe", "SPIR-V", "HLSL", "WGSL B", "llvmpipe/px", "×", "OSL ops", "Cycles ns",
                              "×", "POV-Ray", "POV ns/px", "×");
  for (const auto& r : rows) {
    const CostCell &g = r.cell("glsl"), &o = r.cell("osl"), &p = r.cell("pov");
    std::string glsl = g.error.empty() ? fmt::format("{:>6} {:>6} {:>6} {:>10} {:>6}", count(g, "spirv"),
                                                     count(g, "hlsl_spirv"), count(g, "wgsl_bytes"),
                                                     number(g.number("callgrind_per_pixel"), 1),
                                                     times(g.number("callgrind_relative")))
                                       : fmt::format("{:<38}", "error");
    std::string osl = o.error.empty() ? fmt::format("{:>7} {:>9} {:>6}", count(o, "instructions"),
                                                    ns(o.number("ns_per_pixel")), times(o.number("relative")))
                                      : fmt::format("{:<24}", "error");
    std::string pov = fmt::format("{:>14} {:>9} {:>6}", pov_kind(p), ns(p.number("ns_per_pixel")), times(p.number("relative")));
    s += fmt::format("{:<20} {:<16} {} {} {}\n", r.name, lobes(r), glsl, osl, pov);
  }
  s += fmt::format("the frame alone: SPIR-V {} (HLSL {}), llvmpipe {} instr/px; Cycles, a constant-emission "
                   "shader: {} ns/px\n",
                   b.spirv_empty, b.hlsl_spirv_empty, number(b.callgrind_empty_per_pixel, 1),
                   ns(b.cycles_emission_ns_per_pixel));
  for (const auto& r : rows)
    for (const auto& format : cost_format())
      if (const std::string& e = r.cell(format.target).error; !e.empty())
        s += fmt::format("error: {}: {}\n", r.name, first_line(e));
  return s;
}

namespace {

std::string machine() {
  std::ifstream in("/proc/cpuinfo");
  std::string model = "unknown CPU";
  int cores = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) model = line.substr(line.find(':') + 2);
    if (line.rfind("processor", 0) == 0) ++cores;
  }
  return fmt::format("{}, {} logical cores", model, cores);
}

const char* kMarkdownHeader = "| material | lobe | SPIR-V | HLSL SPIR-V | WGSL bytes | llvmpipe instr/px | × Lambert | shading instr/px | "
                              "OSL ops | Cycles ns/px | × Lambert | shading ns/px | POV-Ray | POV-Ray ns/px | × Lambert |";

// One row of the Markdown table, its cells in kMarkdownHeader's order.
std::string markdown_row(const CostRow& r, const CostBaselines& b) {
  const CostCell &g = r.cell("glsl"), &o = r.cell("osl"), &p = r.cell("pov");
  const double callgrind = g.number("callgrind_per_pixel"), cycles = o.number("ns_per_pixel");
  std::string glsl = g.error.empty()
                         ? fmt::format("{} | {} | {} | {} | {} | {}", count(g, "spirv"), count(g, "hlsl_spirv"),
                                       count(g, "wgsl_bytes"), number(callgrind, 1), times(g.number("callgrind_relative")),
                                       signed_number(shading(callgrind, b.callgrind_empty_per_pixel), 1))
                         : "error | | | | |";
  std::string osl = o.error.empty()
                        ? fmt::format("{} | {} | {} | {}", count(o, "instructions"), ns(cycles), times(o.number("relative")),
                                      signed_number(shading(cycles, b.cycles_emission_ns_per_pixel), 0))
                        : "error | | |";
  return fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", r.name, lobes(r), glsl, osl, pov_kind(p),
                     ns(p.number("ns_per_pixel")), times(p.number("relative")));
}

}  // namespace

std::string costs_markdown(const std::vector<CostRow>& rows, const CostBaselines& b, const CostOptions& o,
                           double wall_seconds) {
  std::string s = "# What the generated code costs\n\n";
  s += "The survey's Appendix B (\"the relative costs of the different lighting models\"), measured: every lobe "
       "model of the catalog, alone at its defaults (`facet::model_materials()`), on each target. Generated by "
       "`facet cost --markdown docs/cost.md`";
  s += fmt::format(" in {:.0f} s of wall time; the test `cost.table` recomputes the counts (SPIR-V, HLSL SPIR-V, WGSL "
                   "bytes, llvmpipe instructions, OSL ops, POV-Ray functions) and fails if they differ from this file's. Do not "
                   "edit it by hand.\n\n",
                   wall_seconds);
  s += fmt::format("**Machine.** {}. **Tools.** {}; {}; {}; {}; Blender {} (OSL {}); {}.\n\n", machine(),
                   b.gl_renderer, b.glslang, b.spirv_tools, b.valgrind, b.blender, b.osl, b.povray);
  s += "**Columns.**\n\n";
  s += fmt::format(
      "- *SPIR-V*: instructions inside function bodies of the material's fragment shader in facet's cost frame "
      "(`codegen/renderers/harness/cost.glsl`: the scene `single`'s sphere ray cast from `gl_FragCoord`, its one point light, "
      "no attenuation, shadow or light loop) after `glslangValidator -G --aml` and `spirv-opt -O`. Every "
      "instruction counts but the structural ones: OpFunction, OpFunctionParameter, OpFunctionEnd, OpLabel, "
      "OpVariable, OpLine, OpNoLine, OpSelectionMerge, OpLoopMerge, OpPhi, OpBranch, OpReturn, OpReturnValue, "
      "OpUnreachable and OpSwitch (spirv-opt's inliner wraps each early return in a one-case switch on a constant). "
      "The frame alone (facet_reflect() returning n + l + v, so the frame's normal, light and view vectors "
      "are computed) is {} of them.\n",
      b.spirv_empty);
  s += fmt::format(
      "- *HLSL SPIR-V*: the same count on the HLSL path: the material as `facet generate --target hlsl` prints it, "
      "under the same frame written as a pixel shader (`codegen/renderers/harness/cost.hlsl`), through "
      "`glslangValidator -D -V -S frag -e main` and `spirv-opt -O`. The frame alone is {} of them (its cbuffer and "
      "`SV_Position`'s flip to GL's y up).\n",
      b.hlsl_spirv_empty);
  s += "- *WGSL bytes*: the size of `facet generate --target wgsl --library` for the material without its comment "
       "and blank lines: what a WebGPU page hands `createShaderModule` besides its entry point. naga validates every "
       "such file in ctest (`wgsl.naga.*`).\n";
  s += fmt::format(
      "- *llvmpipe instr/px*: x86 instructions callgrind counts while Mesa's llvmpipe draws that shader at "
      "{0}×{0}, divided by {0}² (background pixels included): `LP_NUM_THREADS=0` (the draw runs in the calling "
      "thread), `MESA_SHADER_CACHE_DISABLE=true`; every shader is compiled and drawn once untimed (the JIT, with "
      "valgrind's instrumentation still off: `--instr-atstart=no`), then drawn once more untimed, so the measured "
      "draw finds the state its own program left, and then measured, collection on only around `glDrawArrays` + "
      "`glFinish`; all shaders in {1} valgrind processes. Repeated runs give the same counts to the instruction; "
      "drawing a shader in another process's company moves its count by a few tens of instructions (1e-3 per "
      "pixel). The frame alone (as for SPIR-V) is {2} instr/px; *shading instr/px* is the count less the frame's.\n",
      o.callgrind_size, o.jobs, number(b.callgrind_empty_per_pixel, 1));
  s += fmt::format(
      "- *OSL ops*: the ops of the shader Blender's OSL compiler makes from the generated `.osl` (scene `single`, "
      "one light): the `.oso`'s `code ___main___` section, `functioncall` markers excluded (oslc inlines every "
      "function and marks each inlined body with one). The shader includes its frame (normal, view, tangent, the "
      "light's vector and the `trace()` shadow test).\n");
  s += fmt::format(
      "- *Cycles ns/px*: Cycles (CPU, OSL, no bounces) rendering the scene `single` at {0}×{0}; the "
      "time of {1} extra samples, (t(1 + {1} samples) − t(1 sample)) / ({1} · {0}²), so session start, scene sync, "
      "the OSL shader's JIT and read-back cancel; background pixels included; the least of {2} "
      "interleaved rounds, timed as the Blender process's CPU time with Cycles set to two threads (with one, "
      "Blender's caller thread busy-waits beside the render and doubles the CPU time; with two, about one core "
      "works at this size and the CPU time is the render's), nothing else of this command running. A "
      "constant-emission shader on the same sphere takes {3} ns/px: what Cycles spends whatever the shader; *shading "
      "ns/px* subtracts it. Cycles spends most of a sample outside the shader, so the materials differ by tens of "
      "%, and on this shared machine two runs of this command differ by a few % per material (now and then 10 %): "
      "read only the larger differences.\n",
      o.cycles_size, o.cycles_samples, o.cycles_repeats, ns(b.cycles_emission_ns_per_pixel));
  s += fmt::format(
      "- *POV-Ray*: `native` where POV-Ray's own finish is the model, otherwise the number of `#declare … = "
      "function` in the generated scene (`facet generate --target pov`, scene `single`). *POV-Ray ns/px*: the "
      "trace's CPU time POV-Ray reports (`+WT1`, {0}×{0}, no antialiasing, parse time excluded) over {0}², the "
      "least of {1} interleaved rounds.\n\n",
      o.pov_size, o.repeats);
  const std::string header = kMarkdownHeader;
  std::string rule = "|";  // one "---|" a column: the header's bars less one
  for (long i = 1; i < std::count(header.begin(), header.end(), '|'); ++i) rule += "---|";
  s += header + "\n" + rule + "\n";
  for (const auto& r : rows) s += markdown_row(r, b);
  s += fmt::format("\nThe command, to regenerate it: `facet cost --markdown docs/cost.md` (all of it, {:.0f} s here); "
                   "`facet cost --json` prints the same figures for tools.\n",
                   wall_seconds);
  return s;
}

bool callgrind_available() {
#ifdef FACET_LEAK_CHECKED
  return false;
#else
  return true;
#endif
}

std::vector<std::string> stale_costs(const std::string& markdown, const std::vector<CostRow>& rows) {
  // The committed table, by material: its cells in kMarkdownHeader's order.
  std::map<std::string, std::vector<std::string>> committed;
  std::istringstream lines(markdown);
  bool in_table = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == kMarkdownHeader) in_table = true;
    else if (in_table && line.rfind("| `", 0) == 0) {
      std::vector<std::string> cells;
      std::istringstream parts(line.substr(1));
      for (std::string c; std::getline(parts, c, '|');) {
        c.erase(0, c.find_first_not_of(' '));
        c.erase(c.find_last_not_of(' ') + 1);
        cells.push_back(c);
      }
      if (cells.size() >= 13) committed[cells[0].substr(1, cells[0].size() - 2)] = cells;
    } else if (in_table && line.rfind("|---", 0) != 0) {
      in_table = false;
    }
  }
  std::vector<std::string> out;
  if (committed.empty()) out.push_back("no cost table found (its header line must be exactly the one facet writes)");
  for (const auto& r : rows) {
    auto it = committed.find(r.name);
    if (it == committed.end()) {
      out.push_back(fmt::format("{}: not in the table", r.name));
      continue;
    }
    const auto& c = it->second;
    auto check = [&](const char* what, const std::string& was, const std::string& now) {
      if (was != now) out.push_back(fmt::format("{}: {} is {} in the file, {} measured", r.name, what, was, now));
    };
    const CostCell &g = r.cell("glsl"), &o = r.cell("osl");
    if (g.error.empty()) {
      check("SPIR-V", c[2], count(g, "spirv"));
      check("HLSL SPIR-V", c[3], count(g, "hlsl_spirv"));
      check("WGSL bytes", c[4], count(g, "wgsl_bytes"));
      if (g.number("callgrind_per_pixel") > 0) check("llvmpipe instr/px", c[5], number(g.number("callgrind_per_pixel"), 1));
    }
    if (o.error.empty()) check("OSL ops", c[8], count(o, "instructions"));
    check("POV-Ray", c[12], pov_kind(r.cell("pov")));
  }
  return out;
}

}  // namespace facet
