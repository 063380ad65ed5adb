// Cycles + OSL through Blender as a Python module: facet writes each material's
// OSL for the scene, a job file naming them, and runs codegen/renderers/
// cycles_render.py (embedded in the binary) once for the whole batch.
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "renderers/harness.h"
#include "renderers/process.h"
#include "renderers/renderers.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;
using nlohmann::json;

std::string default_python() {
  if (const char* p = std::getenv("FACET_PYTHON"); p && *p) return p;
#ifdef FACET_DEFAULT_PYTHON
  if (fs::exists(FACET_DEFAULT_PYTHON)) return FACET_DEFAULT_PYTHON;
#endif
  return "python3";
}

std::vector<RenderOutcome> render_osl(const std::vector<RenderJob>& jobs, const std::string& python,
                                      std::string& log) {
  std::vector<RenderOutcome> out(jobs.size());
  if (jobs.empty()) return out;
  auto fail_all = [&](const std::string& why) {
    for (auto& o : out) o.error = why;
    return out;
  };
  // One Blender process per scene and size: the job file holds one scene.
  const RenderJob& first = jobs.front();
  for (const auto& j : jobs)
    if (j.scene.name != first.scene.name || j.width != first.width || j.height != first.height || j.workdir != first.workdir)
      return fail_all("render_osl: every job of a batch must share scene, size and workdir");
  fs::create_directories(first.workdir);
  fs::path dir = fs::absolute(first.workdir);
  fs::path script = dir / "cycles_render.py";
  write_file_atomic(script.string(), embedded_harness().at("cycles_render.py"));

  json items = json::array();
  for (const auto& j : jobs) {
    std::string base = job_name(j);
    // One shader per material: the material under test for objects without
    // their own, and each scene material the objects name.
    auto write_osl = [&](const Material& m, const std::string& file) {
      std::string path = (dir / file).string();
      if (!j.code_override.empty()) {
        write_file_atomic(path, j.code_override);
      } else {
        GenerateOptions o;
        o.target = Target::Osl;
        o.scene = j.scene;
        o.source = m.source;
        write_file_atomic(path, generate(m, o));
      }
      return path;
    };
    json item = {{"name", j.material ? j.material->name : j.scene.name}};
    if (j.material) item["osl"] = write_osl(*j.material, base + ".osl");
    json materials = json::object();
    for (const auto& o : j.scene.objects) {
      if (o.material.empty() || materials.contains(o.material)) continue;
      materials[o.material] = write_osl(j.scene.materials.at(o.material), base + "_" + identifier(o.material) + ".osl");
    }
    if (!materials.empty()) item["materials"] = materials;
    std::string output = (dir / (base + "_cycles")).string();
    fs::remove(output + ".pfm");
    fs::remove(output + ".alpha.pfm");
    item["output"] = output;
    items.push_back(item);
  }
  json job = {{"width", first.width}, {"height", first.height}, {"scene", to_json(first.scene)}, {"items", items}};
  fs::path job_file = dir / (identifier(first.scene.name) + "_cycles_job.json");
  write_file_atomic(job_file.string(), job.dump(2));
  fs::remove(job_file.string() + ".result.json");

  ProcessResult r = run_process({python, script.string(), job_file.string()}, dir.string());
  log = r.output;
  if (r.exit_code < 0) return fail_all(fmt::format("cannot run {}: {}", python, r.output));
  json result;
  try {
    result = json::parse(read_file(job_file.string() + ".result.json"));
  } catch (const std::exception& e) {
    return fail_all(fmt::format("Blender ({} {}) exited with {} and wrote no result:\n{}", python, script.string(),
                                r.exit_code, r.output));
  }
  const json& results = result["items"];
  for (size_t i = 0; i < jobs.size(); ++i) {
    RenderOutcome& o = out[i];
    if (i >= results.size()) {
      o.error = "Blender wrote no result for this material";
      continue;
    }
    const json& ri = results[i];
    o.seconds = ri.value("seconds", 0.0);
    if (!ri.value("ok", false)) {
      o.error = ri.value("error", std::string("Blender reported a failure"));
      continue;
    }
    std::string output = items[i]["output"];
    try {
      o.image = read_pfm(output + ".pfm");
      int w = 0, h = 0;
      o.alpha = read_pfm_grey(output + ".alpha.pfm", w, h);
      if (o.image.width != jobs[i].width || o.image.height != jobs[i].height || w != jobs[i].width ||
          h != jobs[i].height) {
        o.error = "Blender wrote an image of the wrong size";
        continue;
      }
      o.ok = true;
      o.log = fmt::format("Blender {}, OSL {}", result.value("blender", "?"), result.value("osl", "?"));
    } catch (const IoError& e) {
      o.error = e.what();
    }
  }
  return out;
}

}  // namespace facet
