// Cycles + OSL through Blender as a Python module ("osl" in the registry):
// facet writes each material's OSL for the scene, a job file naming them, and
// runs codegen/renderers/harness/cycles_render.py (embedded in the binary) once
// for every batch of jobs that share a scene and size.
#include <cmath>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "renderers/backends.h"
#include "renderers/harness.h"
#include "renderers/process.h"
#include "scene/tangents.h"
#include "targets/texture_code.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;
using nlohmann::json;

std::string choose_python(const char* environment, const char* build_python) {
  if (environment && *environment) return environment;
  // Without throwing: a user who may not look into the build's folder gets "python3" (issue 28).
  std::error_code ec;
  if (build_python && *build_python && fs::exists(build_python, ec)) return build_python;
  return "python3";
}

std::string default_python() {
#ifdef FACET_DEFAULT_PYTHON
  return choose_python(std::getenv("FACET_PYTHON"), FACET_DEFAULT_PYTHON);
#else
  return choose_python(std::getenv("FACET_PYTHON"), nullptr);
#endif
}

namespace {

// A Python given as a relative path (--python .venv/bin/python) made absolute: Blender runs
// in the job's folder, where the relative path names nothing. A bare name stays for PATH.
std::string as_run_from_anywhere(const std::string& python) {
  const fs::path p(python);
  return p.is_relative() && p.has_parent_path() ? fs::absolute(p).string() : python;
}

// The sweep's grid side at most.
const int kMaxSweepGrid = 512;

// An image's texels without their alpha, as a binary PPM of 16 bits a channel (k/255 and
// k/65535 are both whole multiples of 1/65535: exact), rows from the top as OpenImageIO reads them.
void write_rgb_copy(const Texels& t, const std::string& path) {
  std::string out = fmt::format("P6\n{} {}\n65535\n", t.width, t.height);
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i)
      for (int k = 0; k < 3; ++k) {
        const long v = std::lround(double(t.at(i, j)[k]) * 65535.0);
        out += char(v >> 8);
        out += char(v & 255);
      }
  write_file_atomic(path, out);
}

// Cycles' image reader (OpenImageIO) premultiplies a PNG's colour by its alpha, which facet's
// rule does not: every image of `materials` whose alpha is below 1 somewhere and whose colour
// is read gets a copy without alpha beside the shaders (GenerateOptions::image_files).
std::map<std::string, std::string> rgb_copies(const std::vector<const Material*>& materials, const fs::path& dir,
                                              const std::string& base) {
  std::map<std::string, std::string> copies;
  for (const Material* m : materials) {
    std::vector<TextureCall> calls = image_calls(compile(*m));
    if (auto a = alpha_call(*m)) calls.push_back(*a);
    for (const TextureCall& c : calls) {
      const Texels& t = *c.texels;
      bool translucent = false;
      for (size_t i = 3; i < t.rgba.size() && !translucent; i += 4) translucent = t.rgba[i] < 1;
      if (c.channel == 3 || !translucent || copies.count(t.path)) continue;
      const std::string path = (dir / fmt::format("{}_image{}.ppm", base, copies.size())).string();
      write_rgb_copy(t, path);
      copies[t.path] = path;
    }
  }
  return copies;
}

// One job's entry in the batch's job file: one shader per material (the
// material under test for objects without their own, and each scene material
// the objects name), and where Blender writes the image.
json batch_item(const RenderJob& j, const fs::path& dir) {
  std::string base = job_name(j);
  std::vector<const Material*> used;
  if (j.material) used.push_back(&*j.material);
  for (const auto& o : j.scene.objects)
    if (!o.material.empty()) used.push_back(&j.scene.materials.at(o.material));
  const std::map<std::string, std::string> copies = j.code_override.empty() ? rgb_copies(used, dir, base)
                                                                            : std::map<std::string, std::string>{};
  auto write_osl = [&](const Material& m, const std::string& file) {
    std::string path = (dir / file).string();
    if (!j.code_override.empty()) {
      write_file_atomic(path, j.code_override);
    } else {
      GenerateOptions o;
      o.target = Target::Osl;
      o.scene = j.scene;
      o.source = m.source;
      o.fallback = j.material ? &*j.material : nullptr;
      o.image_files = copies;
      write_file_atomic(path, generate(m, o));
    }
    return path;
  };
  json item = {{"name", j.material ? j.material->name : j.scene.name}};
  if (j.material) item["osl"] = write_osl(*j.material, base + ".osl");
  json materials = json::object();
  for (const auto& o : j.scene.objects) {
    if (o.material.empty() || materials.contains(o.material)) continue;
    materials[o.material] = write_osl(j.scene.materials.at(o.material),  // numbered: names may fold to one identifier
                                      fmt::format("{}_{}_{}.osl", base, materials.size(), identifier(o.material)));
  }
  if (!materials.empty()) item["materials"] = materials;
  std::string output = (dir / (base + "_cycles")).string();
  fs::remove(output + ".pfm");
  fs::remove(output + ".alpha.pfm");
  item["output"] = output;
  return item;
}

// What Blender wrote for one job: its image and coverage, or why not.
RenderOutcome batch_outcome(const RenderJob& job, const json& result, const json* item_result, const json& item) {
  RenderOutcome o;
  if (!item_result) {
    o.error = "Blender wrote no result for this material";
    return o;
  }
  o.seconds = item_result->value("seconds", 0.0);
  if (!item_result->value("ok", false)) {
    o.error = item_result->value("error", std::string("Blender reported a failure"));
    return o;
  }
  std::string output = item["output"];
  try {
    o.image = read_pfm(output + ".pfm");
    int w = 0, h = 0;
    o.alpha = read_pfm_grey(output + ".alpha.pfm", w, h);
    if (o.image.width != job.width || o.image.height != job.height || w != job.width || h != job.height) {
      o.error = "Blender wrote an image of the wrong size";
      return o;
    }
    o.ok = true;
    o.log = fmt::format("Blender {}, OSL {}", result.value("blender", "?"), result.value("osl", "?"));
  } catch (const IoError& e) {
    o.error = e.what();
  }
  return o;
}

// The corner tangents (scene/tangents.h) of each mesh whose material, in any of `jobs`, has a
// normal map: "facet_tangents0"/"facet_tangents1" of its object, [x, y, z, w] per corner in
// facet's axes, for the harness's corner attributes (docs/textures.md, "Tangent frames").
void add_corner_tangents(json& scene, const std::vector<const RenderJob*>& jobs) {
  const Scene& s = jobs.front()->scene;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    if (s.objects[i].type != Object::Type::Mesh) continue;
    std::set<int> sets;
    for (const RenderJob* j : jobs)
      if (const auto set = s.material_of(i, j->material ? &*j->material : nullptr).frame_uv()) sets.insert(*set);
    for (int set : sets) scene["objects"][i][fmt::format("facet_tangents{}", set)] = mesh_tangents(*s.objects[i].mesh, set);
  }
}

// One Blender process for jobs that share scene, size and workdir; one outcome per job.
std::vector<RenderOutcome> render_batch(const std::vector<const RenderJob*>& jobs, const std::string& python) {
  const RenderJob& first = *jobs.front();
  fs::create_directories(first.folder());
  fs::path dir = fs::absolute(first.folder());
  fs::path script = dir / "cycles_render.py";
  write_file_atomic(script.string(), embedded_harness().at("cycles_render.py"));
  json items = json::array();
  for (const RenderJob* j : jobs) items.push_back(batch_item(*j, dir));
  json job = {{"width", first.width}, {"height", first.height}, {"scene", to_json(first.scene)}, {"items", items}};
  add_corner_tangents(job["scene"], jobs);
  fs::path job_file = dir / (identifier(first.scene.name) + "_cycles_job.json");
  write_file_atomic(job_file.string(), job.dump(2));
  fs::remove(job_file.string() + ".result.json");

  ProcessResult r = run_process({python, script.string(), job_file.string()}, dir.string());
  if (r.exit_code < 0) return failed_renders(jobs.size(), fmt::format("cannot run {}: {}", python, r.output));
  json result;
  try {
    result = json::parse(read_file(job_file.string() + ".result.json"));
  } catch (const std::exception& e) {
    return failed_renders(jobs.size(), fmt::format("Blender ({} {}) exited with {} and wrote no result:\n{}", python,
                                                   script.string(), r.exit_code, r.output));
  }
  const json& results = result["items"];
  std::vector<RenderOutcome> out;
  for (size_t i = 0; i < jobs.size(); ++i)
    out.push_back(batch_outcome(*jobs[i], result, i < results.size() ? &results[i] : nullptr, items[i]));
  return out;
}

// One Blender process for the whole sweep; the shader counts bad values itself.
std::vector<SweepCount> sweep_osl(const std::string& target, const std::vector<SweepJob>& jobs, int grid,
                                  const std::string& python, const std::string& workdir) {
  std::vector<SweepCount> out(jobs.size());
  for (auto& c : out) c.target = target;
  fs::create_directories(workdir);
  fs::path dir = fs::absolute(workdir);
  fs::path script = dir / "cycles_sweep.py";
  write_file_atomic(script.string(), embedded_harness().at("cycles_sweep.py"));
  write_file_atomic((dir / "cycles_render.py").string(), embedded_harness().at("cycles_render.py"));
  json items = json::array();
  for (size_t i = 0; i < jobs.size(); ++i) {
    // Numbered: two materials may share a name.
    const Material& m = jobs[i].material;
    std::string path = (dir / fmt::format("{:03}_{}_sweep.osl", i, identifier(m.name))).string();
    write_file_atomic(path, !jobs[i].source.empty() ? jobs[i].source : osl_sweep_source(m));
    items.push_back({{"name", m.name}, {"osl", path}});
  }
  fs::path job = dir / "sweep_job.json";
  write_file_atomic(job.string(), json({{"size", grid}, {"items", items}}).dump(1));
  fs::remove(job.string() + ".result.json");
  ProcessResult r = run_process({python, script.string(), job.string()}, dir.string());
  json result;
  try {
    result = json::parse(read_file(job.string() + ".result.json"));
  } catch (const std::exception&) {
    return failed_sweeps(jobs.size(), target,
                         fmt::format("Blender exited with {} and wrote no result:\n{}", r.exit_code, r.output));
  }
  for (size_t i = 0; i < jobs.size() && i < result["items"].size(); ++i) {
    const json& ri = result["items"][i];
    if (!ri.value("ok", false)) {
      out[i].error = ri.value("error", std::string("failed"));
      continue;
    }
    out[i].samples = ri.value("samples", size_t(0));
    out[i].nan = ri.value("nan", size_t(0));
    out[i].inf = ri.value("inf", size_t(0));
    out[i].negative = ri.value("negative", size_t(0));
  }
  return out;
}

class CyclesRenderer : public Renderer {
 public:
  CyclesRenderer(const RendererInfo& info, const RendererSettings& settings)
      : info_(info), python_(settings.python.empty() ? default_python() : as_run_from_anywhere(settings.python)) {}
  const RendererInfo& info() const override { return info_; }
  std::string unavailable() const override {
    return find_program(python_).empty() ? fmt::format("cannot run {0}: {0}: not found on PATH", python_) : "";
  }

  // One Blender process per scene, size and workdir, in the order the jobs first name them.
  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override {
    std::vector<RenderOutcome> out(jobs.size());
    std::vector<bool> done(jobs.size(), false);
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (done[i]) continue;
      std::vector<size_t> batch;
      const std::string scene = to_json(jobs[i].scene).dump();
      for (size_t k = i; k < jobs.size(); ++k)
        if (!done[k] && jobs[k].width == jobs[i].width && jobs[k].height == jobs[i].height &&
            jobs[k].workdir == jobs[i].workdir && jobs[k].scene.name == jobs[i].scene.name &&
            (k == i || to_json(jobs[k].scene).dump() == scene))
          batch.push_back(k);
      std::vector<const RenderJob*> batch_jobs;
      for (size_t k : batch) batch_jobs.push_back(&jobs[k]);
      if (progress.step)
        progress.step(fmt::format("Blender renders {} materials on {}", batch.size(), jobs[i].scene.name));
      std::vector<RenderOutcome> outcomes = render_batch(batch_jobs, python_);
      for (size_t b = 0; b < batch.size(); ++b) {
        out[batch[b]] = std::move(outcomes[b]);
        done[batch[b]] = true;
        if (progress.finished) progress.finished(batch[b]);
      }
    }
    return out;
  }

  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override {
    return sweep_osl(info_.name, jobs, std::min(settings.grid, kMaxSweepGrid), python_, settings.workdir);
  }

 private:
  const RendererInfo& info_;
  std::string python_;
};

}  // namespace

std::unique_ptr<Renderer> make_cycles_renderer(const RendererInfo& info, const RendererSettings& settings) {
  return std::make_unique<CyclesRenderer>(info, settings);
}

}  // namespace facet
