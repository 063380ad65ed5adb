#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/io.h"
#include "renderers/process.h"
#include "renderers/renderers.h"
#include "targets/targets.h"

namespace facet {

namespace fs = std::filesystem;

namespace {
// A 16-bit PNG value at or above this may have clipped.
const double kClip = 0.98;
}  // namespace

std::string job_name(const RenderJob& job) {
  return (job.material ? identifier(job.material->name) + "_" : std::string()) + identifier(job.scene.name);
}

RenderOutcome render_pov(const RenderJob& job) {
  RenderOutcome out;
  fs::create_directories(job.workdir);
  const Material* fallback = job.material ? &*job.material : nullptr;
  const std::string base = job_name(job);
  try {
    write_file_atomic((fs::path(job.workdir) / (base + ".pov")).string(),
                      job.code_override.empty()
                          ? generate_pov_scene(job.scene, fallback, fallback ? fallback->source : job.scene.source)
                          : job.code_override);
  } catch (const std::invalid_argument& e) {  // an object without a material, and none given
    out.error = e.what();
    return out;
  }
  PovPlan plan = pov_plan(job.scene, fallback);

  // Exposures are powers of two, exact to undo. The last keeps the brightest pixel below clipping.
  // Bracketing starts at 16, so dim passes (an emission pass, a faint light) keep
  // their precision too, and halves down to the exposure that keeps the brightest below 1.
  std::vector<double> exposures;
  double e = job.bracket ? 16 : 1;
  if (job.bracket) exposures.push_back(e);
  while (job.max_value * e >= kClip) {
    e /= 2;
    if (job.bracket) exposures.push_back(e);
  }
  if (!job.bracket) exposures.push_back(e);

  // Frame f renders light pass f % passes at exposure f / passes.
  const int passes = job.one_run ? 1 : plan.passes, frames = passes * int(exposures.size());
  std::string exposure_table;
  for (size_t k = 0; k < exposures.size(); ++k) exposure_table += fmt::format("{}{}", k ? ", " : "", exposures[k]);
  std::string wrapper = fmt::format(
      "// facet's POV-Ray harness: frame f renders light pass f mod {0} at the (f div {0})-th exposure.\n"
      "#declare Facet_Exposures = array[{1}] {{ {2} }};\n"
      "#declare Facet_Light = {3};\n"
      "#declare Facet_Exposure = Facet_Exposures[div(frame_number, {0})];\n"
      "#include \"{4}.pov\"\n",
      passes, exposures.size(), exposure_table, passes > 1 ? fmt::format("mod(frame_number, {})", passes) : "-1",  // -1: every light at once
      base);
  write_file_atomic((fs::path(job.workdir) / (base + "_harness.pov")).string(), wrapper);
  for (const auto& entry : fs::directory_iterator(job.workdir)) {
    std::string name = entry.path().filename().string();
    if (name.rfind(base + "_frame", 0) == 0) fs::remove(entry.path());
  }

  std::vector<std::string> argv = {"povray", "+I" + base + "_harness.pov", "+O" + base + "_frame.png",
                                   fmt::format("+W{}", job.width), fmt::format("+H{}", job.height), "-A", "+FN16", "+UA",
                                   "File_Gamma=1.0", "-D", "+KFI0", fmt::format("+KFF{}", frames - 1)};
  ProcessResult r = run_process(argv, job.workdir);
  out.seconds = r.seconds;
  out.log = r.output;
  if (r.exit_code != 0) {
    // Lead with POV-Ray's own error lines ("File 'x.pov' line 12: Parse Error: …").
    std::string errors;
    std::istringstream lines(r.output);
    for (std::string line; std::getline(lines, line);)
      if (line.find("Error") != std::string::npos || line.find("error") != std::string::npos) errors += line + " ";
    out.error = r.exit_code < 0 ? r.output
                                : fmt::format("povray exited with {}: {}\n{}", r.exit_code, errors, r.output);
    return out;
  }
  // POV-Ray numbers frames with as many digits as the last one needs.
  std::map<int, std::string> files;
  for (const auto& entry : fs::directory_iterator(job.workdir)) {
    std::string name = entry.path().filename().string();
    std::string prefix = base + "_frame";
    if (name.rfind(prefix, 0) != 0 || entry.path().extension() != ".png") continue;
    std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - 4);
    if (!digits.empty() && std::all_of(digits.begin(), digits.end(), ::isdigit))
      files[std::stoi(digits)] = entry.path().string();
  }
  if (frames == 1 && files.empty() && fs::exists(fs::path(job.workdir) / (base + "_frame.png")))
    files[0] = (fs::path(job.workdir) / (base + "_frame.png")).string();
  if (int(files.size()) != frames) {
    out.error = fmt::format("povray wrote {} of {} frames:\n{}", files.size(), frames, r.output);
    return out;
  }

  out.image = Image(job.width, job.height);
  out.alpha = read_png_alpha(files[0]);  // coverage (+UA); the same in every frame
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Image> frames_of_pass;
    for (size_t k = 0; k < exposures.size(); ++k) {
      frames_of_pass.push_back(read_png(files[int(k) * passes + pass]));
      if (frames_of_pass.back().width != job.width || frames_of_pass.back().height != job.height) {
        out.error = "povray wrote an image of the wrong size";
        return out;
      }
    }
    for (size_t i = 0; i < out.image.rgb.size(); ++i) {
      // The brightest exposure that did not clip.
      size_t k = 0;
      while (k + 1 < exposures.size() && frames_of_pass[k].rgb[i] >= kClip) ++k;
      out.image.rgb[i] += float(frames_of_pass[k].rgb[i] / exposures[k]);
    }
  }
  out.ok = true;
  return out;
}

}  // namespace facet
