#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "facet/io.h"
#include "facet/process.h"
#include "facet/renderers.h"
#include "facet/targets.h"

namespace facet {

namespace fs = std::filesystem;

RenderOutcome render_pov(const RenderJob& job) {
  RenderOutcome out;
  fs::create_directories(job.workdir);
  GenerateOptions o;
  o.target = Target::Pov;
  o.scene = job.scene;
  o.source = job.material.source;
  const std::string base = identifier(job.material.name) + "_" + identifier(job.scene.name);
  write_file_atomic((fs::path(job.workdir) / (base + ".pov")).string(), generate(job.material, o));
  PovPlan plan = pov_plan(job.material, job.scene);

  // 16-bit PNGs clip at 1: scale by a power of two (exact to undo) that keeps the brightest pixel below 1.
  double exposure = 1;
  while (job.max_value * exposure >= 0.98) exposure /= 2;

  out.image = Image(job.width, job.height);
  for (int pass = 0; pass < plan.passes; ++pass) {
    std::string png = plan.passes == 1 ? base + ".png" : fmt::format("{}_light{}.png", base, pass);
    std::vector<std::string> argv = {"povray", "+I" + base + ".pov", "+O" + png, fmt::format("+W{}", job.width),
                                     fmt::format("+H{}", job.height), "-A", "+FN16", "File_Gamma=1.0", "-D",
                                     fmt::format("Declare=Facet_Exposure={}", exposure)};
    if (plan.passes > 1) argv.push_back(fmt::format("Declare=Facet_Light={}", pass));
    ProcessResult r = run_process(argv, job.workdir);
    out.seconds += r.seconds;
    out.log += r.output;
    if (r.exit_code != 0) {
      out.error = r.exit_code < 0 ? r.output : fmt::format("povray exited with {}: {}", r.exit_code, r.output);
      return out;
    }
    Image img = read_png((fs::path(job.workdir) / png).string());
    if (img.width != job.width || img.height != job.height) {
      out.error = "povray wrote an image of the wrong size";
      return out;
    }
    for (size_t i = 0; i < img.rgb.size(); ++i) out.image.rgb[i] += float(img.rgb[i] / exposure);
  }
  out.ok = true;
  return out;
}

}  // namespace facet
