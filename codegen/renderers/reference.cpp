// The C++ reference ("reference" in the registry): facet's ray caster shading
// with the C++ reference (reference/raycaster.h), the image the others are
// compared with, and the reference's sweep over the grid and random sets.
#include <chrono>

#include "core/parallel.h"
#include "reference/interpreter.h"
#include "reference/raycaster.h"
#include "renderers/backends.h"
#include "renderers/sweep.h"

namespace facet {

namespace {

// The reference sweeps this grid whatever the targets' (and random sets besides).
const int kSweepGrid = 512;
// Its materials two at a time: the targets' sweeps run one after another, the reference on both cores.
const unsigned kSweepThreads = 2;

class ReferenceRenderer : public Renderer {
 public:
  explicit ReferenceRenderer(const RendererInfo& info) : info_(info) {}
  const RendererInfo& info() const override { return info_; }

  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override {
    return render_each(jobs, progress, [&](const RenderJob& job) { return render_one(job); });
  }

  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override {
    std::vector<SweepCount> out(jobs.size());
    parallel_for(jobs.size(), kSweepThreads, [&](size_t i) {
      const Material& m = jobs[i].material;
      Reference ref(m);
      out[i] = sweep_directions(kSweepGrid, settings.random, Vec3(m.tangent_axis),
                                [&](const Vec3& n, const Vec3& l, const Vec3& v, const Vec3& t) {
                                  return ref.reflectance(n, l, v, t);
                                });
      out[i].target = info_.name;
    });
    return out;
  }

 private:
  RenderOutcome render_one(const RenderJob& job) const {
    RenderOutcome out;
    auto start = std::chrono::steady_clock::now();
    try {
      Render r = job.material ? render_reference(*job.material, job.scene, job.width, job.height)
                              : render_reference(job.scene, job.width, job.height);
      out.image = std::move(r.image);
      for (int object : r.object) out.alpha.push_back(object >= 0 ? 1.0f : 0.0f);
      out.ok = true;
    } catch (const std::exception& e) {  // an object without a material, and none given
      out.error = e.what();
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }

  const RendererInfo& info_;
};

}  // namespace

std::unique_ptr<Renderer> make_reference_renderer(const RendererInfo& info, const RendererSettings&) {
  return std::make_unique<ReferenceRenderer>(info);
}

}  // namespace facet
