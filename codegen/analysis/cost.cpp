// What the generated code costs (facet/cost.h): counts from the compilers,
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
#include <thread>

#include <fmt/format.h>
#include <valgrind/callgrind.h>

#include "catalog/program.h"
#include "core/io.h"
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

SpirvCount spirv_instructions(const std::string& glsl, const std::string& workdir, const std::string& name) {
  SpirvCount out;
  fs::create_directories(workdir);
  const fs::path base = fs::path(workdir) / identifier(name);
  const std::string frag = base.string() + ".frag", spv = base.string() + ".spv", opt = base.string() + ".opt.spv",
                    dis = base.string() + ".opt.spvasm";
  write_file_atomic(frag, glsl);
  auto step = [&](const std::vector<std::string>& argv) {
    ProcessResult r = run_process(argv);
    if (r.exit_code != 0) out.error = fmt::format("{} exited with {}: {}", argv[0], r.exit_code, r.output);
    return r.exit_code == 0;
  };
  if (!step({"glslangValidator", "-G", "--aml", "-o", spv, frag}) || !step({"spirv-opt", "-O", spv, "-o", opt}) ||
      !step({"spirv-dis", opt, "-o", dis}))
    return out;
  out.disassembly = read_file(dis);
  out.instructions = count_spirv(out.disassembly);
  return out;
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
  std::vector<std::thread> threads;
  for (size_t k = 0; k < jobs; ++k)
    threads.emplace_back(callgrind_chunk, std::cref(shaders), std::cref(chunks[k]), width, height, std::cref(facet),
                         std::cref(dir), int(k), std::ref(out));
  for (auto& t : threads) t.join();
  return out;
}


// ---------------------------------------------------------------- Cycles (OSL)

namespace {

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
      ProcessResult r = run_process({"povray", "+I" + file, "-F", fmt::format("+W{}", o.pov_size),
                                     fmt::format("+H{}", o.pov_size), "-A", "+WT1", "-D", "-GR", "File_Gamma=1.0"},
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

// ---------------------------------------------------------------- the table

bool is_baseline(const Material& m) {
  return m.name == "lambert" && m.diffuse && !m.specular && m.diffuse->def->name == "lambert";
}

double ratio(double x, double base) { return base > 0 && x > 0 ? x / base : 0; }

}  // namespace

std::vector<CostRow> measure_costs(const std::vector<Material>& materials, const CostOptions& options,
                                   const CostProgress& progress, CostBaselines* baselines) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  std::vector<Material> ms = materials;
  if (std::none_of(ms.begin(), ms.end(), is_baseline))
    ms.insert(ms.begin(), lobe_material(default_spec(*find_model("diffuse", "lambert")), "lambert"));
  const fs::path dir = fs::absolute(options.workdir.empty() ? (fs::temp_directory_path() / "facet-cost").string()
                                                            : options.workdir);
  fs::create_directories(dir);

  std::vector<CostRow> rows(ms.size());
  for (size_t i = 0; i < ms.size(); ++i) {
    rows[i].name = ms[i].name;
    rows[i].material = ms[i].source.empty() ? ms[i].name : ms[i].source;
    if (ms[i].diffuse) rows[i].diffuse = ms[i].diffuse->def->name;
    if (ms[i].specular) rows[i].specular = ms[i].specular->def->name;
  }
  CostBaselines base;

  // The counts: compilers only, seconds.
  say(fmt::format("GLSL: SPIR-V of {} shaders (glslangValidator, spirv-opt -O)", ms.size() + 1));
  std::vector<ShaderDraw> draws;
  const auto uniforms = cost_frame_uniforms(options.callgrind_size, options.callgrind_size);
  for (size_t i = 0; i < ms.size(); ++i) {
    ShaderDraw d{ms[i].name, cost_fragment_source(ms[i]), uniforms};
    SpirvCount s = spirv_instructions(d.fragment_source, (dir / "glsl").string(), fmt::format("{}_{:03}", ms[i].name, i));
    rows[i].glsl.spirv = s.instructions;
    rows[i].glsl.error = s.error;
    draws.push_back(d);
  }
  draws.push_back({"(empty frame)", cost_frame_source(kEmptyLibrary), uniforms});
  base.spirv_empty = spirv_instructions(draws.back().fragment_source, (dir / "glsl").string(), "empty").instructions;
  std::vector<PovCost> pov(ms.size());
  pov_counts(ms, dir / "pov", pov);

  // callgrind on every core, then the timings, one per core.
  if (options.callgrind) {
    say(fmt::format("GLSL: llvmpipe draws of {} shaders under callgrind, {} valgrind processes",
                    draws.size(), options.jobs));
    std::vector<CallgrindCount> counts =
        callgrind_draws(draws, options.callgrind_size, options.callgrind_size, options, (dir / "callgrind").string());
    for (size_t i = 0; i < ms.size(); ++i) {
      if (!counts[i].error.empty() && rows[i].glsl.error.empty()) rows[i].glsl.error = counts[i].error;
      rows[i].glsl.callgrind_per_pixel = counts[i].per_pixel;
    }
    base.callgrind_empty_per_pixel = counts.back().per_pixel;
  }
  // The timings one at a time: Cycles renders on one thread while Blender's
  // caller busy-waits on the other core, and a third process would slow either.
  if (options.timings) {
    say("POV-Ray: tracing every scene");
    pov_timings(ms, options, dir / "pov", pov);
  }
  say(options.timings ? "OSL: Blender compiles and times every shader in Cycles" : "OSL: Blender compiles every shader");
  OslFigures osl = cycles_costs(ms, options, dir / "osl");

  base.cycles_emission_ns_per_pixel = osl.emission_ns_per_pixel;
  base.blender = osl.blender;
  base.osl = osl.osl;
  for (size_t i = 0; i < ms.size(); ++i) {
    rows[i].osl = osl.rows[i];
    rows[i].pov = pov[i];
  }
  // Relative to Lambert.
  const CostRow& lambert = rows[size_t(std::find_if(ms.begin(), ms.end(), is_baseline) - ms.begin())];
  const double cg = lambert.glsl.callgrind_per_pixel, cy = lambert.osl.ns_per_pixel, pv = lambert.pov.ns_per_pixel;
  for (auto& r : rows) {
    r.glsl.callgrind_relative = ratio(r.glsl.callgrind_per_pixel, cg);
    r.osl.relative = ratio(r.osl.ns_per_pixel, cy);
    r.pov.relative = ratio(r.pov.ns_per_pixel, pv);
  }
  if (baselines) {
    base.povray = tool_version({"povray", "--version"}, "POV-Ray");
    base.glslang = tool_version({"glslangValidator", "--version"}, "Glslang");
    base.spirv_tools = tool_version({"spirv-opt", "--version"}, "SPIRV-Tools");
    if (options.callgrind) base.valgrind = tool_version({"valgrind", "--version"}, "valgrind");
    GlRenderer gl;
    base.gl_renderer = gl.ok() ? gl.description() : gl.error();
    *baselines = base;
  }
  return rows;
}

// ---------------------------------------------------------------- output

namespace {

json or_null(double x) { return x > 0 ? json(x) : json(nullptr); }

// x − frame: the shading alone, without what the frame (or Cycles' own path)
// costs; absent when either was not measured. Timings may come out a little below
// the frame's by noise, so the difference keeps its sign.
std::optional<double> shading(double x, double frame) {
  if (x > 0 && frame > 0) return x - frame;
  return std::nullopt;
}
json or_null(const std::optional<double>& x) { return x ? json(*x) : json(nullptr); }
std::string signed_number(const std::optional<double>& x, int decimals) {
  return x ? fmt::format("{:.{}f}", *x, decimals) : "–";
}

std::string lobes(const CostRow& r) {
  if (!r.diffuse.empty() && !r.specular.empty()) return r.diffuse + " + " + r.specular;
  return r.diffuse.empty() ? r.specular : r.diffuse;
}

std::string number(double x, int decimals) { return x > 0 ? fmt::format("{:.{}f}", x, decimals) : "–"; }
std::string times(double x) { return x > 0 ? fmt::format("{:.2f}", x) : "–"; }
std::string ns(double x) { return x > 0 ? fmt::format("{:.{}f}", x, x >= 100 ? 0 : 1) : "–"; }

std::string pov_kind(const PovCost& p) {
  if (!p.error.empty()) return "error";
  return p.native ? "native" : fmt::format("{} functions", p.functions);
}

}  // namespace

json costs_json(const std::vector<CostRow>& rows, const CostBaselines& b) {
  json out = {{"baseline", "lambert"}, {"rows", json::array()}};
  for (const auto& r : rows) {
    json row = {{"name", r.name},
                {"material", r.material},
                {"diffuse", r.diffuse.empty() ? json(nullptr) : json(r.diffuse)},
                {"specular", r.specular.empty() ? json(nullptr) : json(r.specular)}};
    if (!r.glsl.error.empty()) row["glsl"] = {{"error", r.glsl.error}};
    else
      row["glsl"] = {{"spirv", r.glsl.spirv},
                     {"callgrind_per_pixel", or_null(r.glsl.callgrind_per_pixel)},
                     {"callgrind_relative", or_null(r.glsl.callgrind_relative)},
                     {"callgrind_shading_per_pixel", or_null(shading(r.glsl.callgrind_per_pixel, b.callgrind_empty_per_pixel))}};
    if (!r.osl.error.empty()) row["osl"] = {{"error", r.osl.error}};
    else
      row["osl"] = {{"instructions", r.osl.instructions},
                    {"ns_per_pixel", or_null(r.osl.ns_per_pixel)},
                    {"relative", or_null(r.osl.relative)},
                    {"shading_ns_per_pixel", or_null(shading(r.osl.ns_per_pixel, b.cycles_emission_ns_per_pixel))}};
    if (!r.pov.error.empty()) row["pov"] = {{"error", r.pov.error}};
    else
      row["pov"] = {{"native", r.pov.native},
                    {"functions", r.pov.native ? json(nullptr) : json(r.pov.functions)},
                    {"ns_per_pixel", or_null(r.pov.ns_per_pixel)},
                    {"relative", or_null(r.pov.relative)}};
    out["rows"].push_back(row);
  }
  out["frame"] = {{"glsl_spirv", b.spirv_empty},
                  {"glsl_callgrind_per_pixel", or_null(b.callgrind_empty_per_pixel)},
                  {"osl_emission_ns_per_pixel", or_null(b.cycles_emission_ns_per_pixel)}};
  out["tools"] = {{"gl_renderer", b.gl_renderer}, {"blender", b.blender},     {"osl", b.osl},
                  {"povray", b.povray},           {"glslang", b.glslang},     {"spirv_tools", b.spirv_tools},
                  {"valgrind", b.valgrind}};
  return out;
}

std::string costs_table(const std::vector<CostRow>& rows, const CostBaselines& b) {
  std::string s = fmt::format("{:<20} {:<16} {:>6} {:>10} {:>6} {:>7} {:>9} {:>6} {:>14} {:>9} {:>6}\n", "material",
                              "lobe", "SPIR-V", "llvmpipe/px", "×", "OSL ops", "Cycles ns", "×", "POV-Ray",
                              "POV ns/px", "×");
  for (const auto& r : rows) {
    std::string glsl = r.glsl.error.empty()
                           ? fmt::format("{:>6} {:>10} {:>6}", r.glsl.spirv, number(r.glsl.callgrind_per_pixel, 1),
                                         times(r.glsl.callgrind_relative))
                           : fmt::format("{:<24}", "error");
    std::string osl = r.osl.error.empty() ? fmt::format("{:>7} {:>9} {:>6}", r.osl.instructions, ns(r.osl.ns_per_pixel),
                                                        times(r.osl.relative))
                                          : fmt::format("{:<24}", "error");
    std::string pov = fmt::format("{:>14} {:>9} {:>6}", pov_kind(r.pov), ns(r.pov.ns_per_pixel), times(r.pov.relative));
    s += fmt::format("{:<20} {:<16} {} {} {}\n", r.name, lobes(r), glsl, osl, pov);
  }
  s += fmt::format("the frame alone: SPIR-V {}, llvmpipe {} instr/px; Cycles, a constant-emission shader: {} ns/px\n",
                   b.spirv_empty, number(b.callgrind_empty_per_pixel, 1), ns(b.cycles_emission_ns_per_pixel));
  for (const auto& r : rows)
    for (const auto* e : {&r.glsl.error, &r.osl.error, &r.pov.error})
      if (!e->empty()) s += fmt::format("error: {}: {}\n", r.name, first_line(*e));
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

const char* kMarkdownHeader = "| material | lobe | SPIR-V | llvmpipe instr/px | × Lambert | shading instr/px | OSL ops | "
                              "Cycles ns/px | × Lambert | shading ns/px | POV-Ray | POV-Ray ns/px | × Lambert |";

}  // namespace

std::string costs_markdown(const std::vector<CostRow>& rows, const CostBaselines& b, const CostOptions& o,
                           double wall_seconds) {
  std::string s = "# What the generated code costs\n\n";
  s += "The survey's Appendix B (\"the relative costs of the different lighting models\"), measured: every lobe "
       "model of the catalog, alone at its defaults (`facet::model_materials()`), on each target. Generated by "
       "`facet cost --markdown docs/cost.md`";
  s += fmt::format(" in {:.0f} s of wall time; the test `cost.table` recomputes the counts (SPIR-V, llvmpipe "
                   "instructions, OSL ops, POV-Ray functions) and fails if they differ from this file's. Do not "
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
  s += std::string(kMarkdownHeader) + "\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::string glsl = r.glsl.error.empty()
                           ? fmt::format("{} | {} | {} | {}", r.glsl.spirv, number(r.glsl.callgrind_per_pixel, 1),
                                         times(r.glsl.callgrind_relative),
                                         signed_number(shading(r.glsl.callgrind_per_pixel, b.callgrind_empty_per_pixel), 1))
                           : "error | | |";
    std::string osl = r.osl.error.empty()
                          ? fmt::format("{} | {} | {} | {}", r.osl.instructions, ns(r.osl.ns_per_pixel), times(r.osl.relative),
                                        signed_number(shading(r.osl.ns_per_pixel, b.cycles_emission_ns_per_pixel), 0))
                          : "error | | |";
    s += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", r.name, lobes(r), glsl, osl, pov_kind(r.pov),
                     ns(r.pov.ns_per_pixel), times(r.pov.relative));
  }
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
      if (cells.size() >= 12) committed[cells[0].substr(1, cells[0].size() - 2)] = cells;
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
    if (r.glsl.error.empty()) {
      check("SPIR-V", c[2], std::to_string(r.glsl.spirv));
      if (r.glsl.callgrind_per_pixel > 0) check("llvmpipe instr/px", c[3], number(r.glsl.callgrind_per_pixel, 1));
    }
    if (r.osl.error.empty()) check("OSL ops", c[6], std::to_string(r.osl.instructions));
    check("POV-Ray", c[10], pov_kind(r.pov));
  }
  return out;
}

}  // namespace facet
