// POV-Ray 3.7 ("pov" in the registry): the generated scene, one frame per pass
// (see pov_plan) and exposure, each a linear 16-bit PNG with antialiasing off,
// rendered as one animation; the passes are summed and divided by their exposure.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include <fmt/format.h>

#include "core/io.h"
#include "core/parallel.h"
#include "renderers/backends.h"
#include "renderers/process.h"
#include "renderers/sweep.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;

namespace {

// A 16-bit PNG value at or above this may have clipped.
const double kClip = 0.98;
// The sweep's grid side at most: POV-Ray's function pigments are slow.
const int kMaxSweepGrid = 256;
// POV-Ray's start-up is single-threaded: two renders at a time.
const unsigned kProcesses = 2;

// Exposures are powers of two, exact to undo. The last keeps the brightest pixel below clipping.
// Bracketing starts at 16, so dim passes (an emission pass, a faint light) keep
// their precision too, and steps down by `ratio` to the exposure that keeps the brightest
// below 1: each pixel is read from the brightest exposure it does not clip in, at least
// kClip / ratio of full scale, so its relative error is at most ratio · ½ / (65535 · kClip).
std::vector<double> exposures(const RenderJob& job, double ratio) {
  std::vector<double> out;
  const bool bracket = ratio > 1;
  double e = bracket ? 16 : 1;
  if (bracket) out.push_back(e);
  while (job.max_value * e >= kClip) {
    e /= bracket ? ratio : 2;
    if (bracket) out.push_back(e);
  }
  if (!bracket) out.push_back(e);
  return out;
}

// The bracketing ratio a job takes (1: one exposure). --exact's is 2: 16-bit relative
// precision everywhere. A comparison's tolerance t allows an error of t · max(1, |ref|),
// of which the exposures may take half (the rest is the renderers' own difference). One
// exposure e errs by ½ / (65535 e) a pass, absolute: it serves while passes · ½ / (65535 e)
// ≤ t / 2. Bracketed, a pass's value errs by at most ratio · ½ / (65535 · kClip) of itself
// (and the passes' values add up to the pixel's), and the dimmest by ½ / (65535 · 16) a pass:
// the coarsest power-of-two ratio within t / 2.
double bracket_ratio(const RenderJob& job, int passes) {
  if (job.bracket) return 2;
  if (job.tolerance <= 0) return 1;
  const double e = exposures(job, 1).back();
  if (passes * 0.5 / (65535 * e) <= job.tolerance / 2) return 1;
  double ratio = 2;
  while (2 * ratio * 0.5 / (65535 * kClip) <= job.tolerance / 2) ratio *= 2;
  return ratio;
}

// The harness that includes BASE.pov: frame f renders light pass f % passes at exposure f / passes.
std::string harness(const std::string& base, int passes, const std::vector<double>& exposures) {
  std::string table;
  for (size_t k = 0; k < exposures.size(); ++k) table += fmt::format("{}{}", k ? ", " : "", exposures[k]);
  return fmt::format(
      "// facet's POV-Ray harness: frame f renders light pass f mod {0} at the (f div {0})-th exposure.\n"
      "#declare Facet_Exposures = array[{1}] {{ {2} }};\n"
      "#declare Facet_Light = {3};\n"
      "#declare Facet_Exposure = Facet_Exposures[div(frame_number, {0})];\n"
      "#include \"{4}.pov\"\n",
      passes, exposures.size(), table, passes > 1 ? fmt::format("mod(frame_number, {})", passes) : "-1",  // -1: every light at once
      base);
}

// POV-Ray's failure: its own error lines first ("File 'x.pov' line 12: Parse Error: …").
std::string povray_error(const ProcessResult& r) {
  if (r.exit_code < 0) return r.output;
  std::string errors;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (line.find("Error") != std::string::npos || line.find("error") != std::string::npos) errors += line + " ";
  // A write that failed (a full disk, a file-size limit) POV-Ray reports only as this line.
  if (r.output.find("Cannot access data in file") != std::string::npos)
    errors = "it could not write its image (is the disk full, or a file-size limit reached?): " + errors;
  return fmt::format("povray exited with {}: {}\n{}", r.exit_code, errors, r.output);
}

// Removes the files in `dir` whose names start with `prefix`: POV-Ray's images, partial where
// it failed, and the BASE.pov-state it leaves when it stops before the end (a full disk).
void remove_starting_with(const std::string& dir, const std::string& prefix) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) fs::remove(entry.path(), ec);
}

// The frames BASE_frameN.png by N: POV-Ray numbers them with as many digits as the last one needs.
std::map<int, std::string> frame_files(const std::string& dir, const std::string& base, int frames) {
  std::map<int, std::string> files;
  const std::string prefix = base + "_frame";
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || entry.path().extension() != ".png") continue;
    std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - 4);
    if (!digits.empty() && std::all_of(digits.begin(), digits.end(), ::isdigit))
      files[std::stoi(digits)] = entry.path().string();
  }
  if (frames == 1 && files.empty() && fs::exists(fs::path(dir) / (prefix + ".png")))
    files[0] = (fs::path(dir) / (prefix + ".png")).string();
  return files;
}

// Each pass's brightest exposure that did not clip, undone, summed over the passes.
void combine_frames(const RenderJob& job, std::map<int, std::string>& files, int passes,
                    const std::vector<double>& exposures, RenderOutcome& out) {
  out.image = Image(job.width, job.height);
  out.alpha = read_png_alpha(files[0]);  // coverage (+UA); the same in every frame
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Image> frames_of_pass;
    for (size_t k = 0; k < exposures.size(); ++k) {
      frames_of_pass.push_back(read_png(files[int(k) * passes + pass]));
      if (frames_of_pass.back().width != job.width || frames_of_pass.back().height != job.height) {
        out.error = "povray wrote an image of the wrong size";
        return;
      }
    }
    for (size_t i = 0; i < out.image.rgb.size(); ++i) {
      size_t k = 0;
      while (k + 1 < exposures.size() && frames_of_pass[k].rgb[i] >= kClip) ++k;
      out.image.rgb[i] += float(frames_of_pass[k].rgb[i] / exposures[k]);
    }
  }
  out.ok = true;
}

RenderOutcome render_pov(const RenderJob& job) {
  RenderOutcome out;
  const std::string dir = job.folder();
  fs::create_directories(dir);
  const Material* fallback = job.material ? &*job.material : nullptr;
  const std::string base = job_name(job);
  int passes = 1;
  try {
    // The files beside the scene (a mesh's lists and data image) come with an overriding code too.
    PovOutput pov = generate_pov_files(job.scene, fallback, fallback ? fallback->source : job.scene.source,
                                       job.pov_route, base);
    if (!job.code_override.empty()) pov.code = job.code_override;
    passes = job.one_run ? 1 : pov.plan.passes;
    for (const auto& f : pov.files) write_file_atomic((fs::path(dir) / f.name).string(), f.write);
    write_file_atomic((fs::path(dir) / (base + ".pov")).string(), pov.code);
  } catch (const std::invalid_argument& e) {  // an object without a material, and none given
    out.error = e.what();
    return out;
  }
  const double ratio = bracket_ratio(job, passes);
  const std::vector<double> exposure = exposures(job, ratio);
  if (ratio > 1 && !job.bracket)
    out.note = fmt::format("POV-Ray: the scene's range (brightest {:.4g}) is more than one 16-bit exposure holds to "
                           "the tolerance; exposures bracketed, {} of them from 16 down by ×{:g}",
                           job.max_value, exposure.size(), ratio);
  const int frames = passes * int(exposure.size());
  write_file_atomic((fs::path(dir) / (base + "_harness.pov")).string(), harness(base, passes, exposure));
  remove_starting_with(dir, base + "_frame");  // an earlier run's frames

  ProcessResult r = run_povray({"+I" + base + "_harness.pov", "+O" + base + "_frame.png", fmt::format("+W{}", job.width),
                                 fmt::format("+H{}", job.height), "-A", "+FN16", "+UA", "File_Gamma=1.0", "-D", "+KFI0",
                                 fmt::format("+KFF{}", frames - 1)},
                                dir);
  out.seconds = r.seconds;
  out.log = r.output;
  if (r.exit_code != 0) {
    out.error = povray_error(r);
    remove_starting_with(dir, base + "_frame");  // its partial frames and .pov-state, in a --workdir too
    return out;
  }
  std::map<int, std::string> files = frame_files(dir, base, frames);
  if (int(files.size()) != frames) {
    out.error = fmt::format("povray wrote {} of {} frames:\n{}", files.size(), frames, r.output);
    remove_starting_with(dir, base + "_frame");
    return out;
  }
  combine_frames(job, files, passes, exposure, out);
  return out;
}

// The pigment shows whether each channel is finite and ≥ 0 (POV-Ray renders
// NaN black, so the test is made inside the function).
SweepCount sweep_pov(const std::string& target, const SweepJob& job, int grid, const std::string& workdir) {
  SweepCount c;
  c.target = target;
  fs::create_directories(workdir);
  std::string base = identifier(job.material.name) + "_sweep";
  write_file_atomic((fs::path(workdir) / (base + ".pov")).string(),
                    job.source.empty() ? generate_pov_sweep(job.material) : job.source);
  ProcessResult r = run_povray({"+I" + base + ".pov", "+O" + base + ".png", fmt::format("+W{}", grid),
                                 fmt::format("+H{}", grid), "-A", "+FN16", "File_Gamma=1.0", "-D"},
                                workdir);
  if (r.exit_code != 0) {
    c.error = povray_error(r);
    std::error_code ignored;  // a partial image and the .pov-state POV-Ray leaves when it stops early
    fs::remove(fs::path(workdir) / (base + ".png"), ignored);
    fs::remove(fs::path(workdir) / (base + ".pov-state"), ignored);
    return c;
  }
  Image img = read_png((fs::path(workdir) / (base + ".png")).string());
  // Each channel shows 1 where the value was finite and ≥ 0; the function cannot
  // tell NaN from Inf from negative, so a failure counts as NaN.
  for (size_t i = 0; i < img.rgb.size(); i += 3) {
    ++c.samples;
    for (int k = 0; k < 3; ++k)
      if (img.rgb[i + size_t(k)] < 0.5f) ++c.nan;
  }
  return c;
}

class PovRenderer : public Renderer {
 public:
  explicit PovRenderer(const RendererInfo& info) : info_(info) {}
  const RendererInfo& info() const override { return info_; }
  std::string unavailable() const override {
    return find_program("povray").empty() ? "povray: not found on PATH" : "";
  }

  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override {
    if (std::string why = unavailable(); !why.empty()) return failed_renders(jobs.size(), why);
    std::vector<RenderOutcome> out(jobs.size());
    std::mutex mutex;
    parallel_for(jobs.size(), kProcesses, [&](size_t i) {
      out[i] = render_pov(jobs[i]);
      std::lock_guard<std::mutex> lock(mutex);
      if (progress.finished) progress.finished(i);
    });
    return out;
  }

  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override {
    if (std::string why = unavailable(); !why.empty()) return failed_sweeps(jobs.size(), info_.name, why);
    std::vector<SweepCount> out;
    for (const auto& j : jobs) out.push_back(sweep_pov(info_.name, j, std::min(settings.grid, kMaxSweepGrid), settings.workdir));
    return out;
  }

 private:
  const RendererInfo& info_;
};

}  // namespace

std::unique_ptr<Renderer> make_povray_renderer(const RendererInfo& info, const RendererSettings&) {
  return std::make_unique<PovRenderer>(info);
}

}  // namespace facet
