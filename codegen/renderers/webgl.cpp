// WebGL2 renderer ("webgl"): the generated OpenGL ES 3.00 shader in headless
// Chromium (ANGLE on SwiftShader). The GL renderer casts each material pass's
// G-buffer (renderers/gbuffer.h); a self-contained page (harness/webgl.html) holds the
// G-buffer as base64 float32, the ES shading pass (templates/glsl/gbuffer_shade.glsl)
// and the light values, and draws it into an RGBA32F framebuffer; `chromium --dump-dom`
// hands back the page with the float pixels in it.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/program.h"
#include "core/io.h"
#include "renderers/backends.h"
#include "renderers/gbuffer.h"
#include "renderers/harness.h"
#include "renderers/opengl.h"
#include "renderers/process.h"
#include "renderers/sweep.h"
#include "targets/targets.h"
#include "targets/texture_code.h"

namespace facet {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kVertexShader = R"(#version 300 es
// One triangle covering the viewport; the G-buffer holds the rays' hits.
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string base64(const std::vector<float>& values) {
  const auto* b = reinterpret_cast<const unsigned char*>(values.data());
  const size_t n = values.size() * sizeof(float);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (size_t i = 0; i < n; i += 3) {
    const unsigned v = unsigned(b[i]) << 16 | (i + 1 < n ? unsigned(b[i + 1]) << 8 : 0u) | (i + 2 < n ? b[i + 2] : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= (n - i) ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// The floats of base64 `text` (whitespace skipped); false when it is not whole floats of base64.
bool unbase64(const std::string& text, std::vector<float>& values) {
  std::string bytes;
  unsigned v = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
    const char* at = std::strchr(kAlphabet, c);
    if (!at || !c) return false;
    v = (v << 6) | unsigned(at - kAlphabet);
    if ((bits += 6) >= 8) bytes += char((v >> (bits -= 8)) & 255);
  }
  if (bytes.size() % sizeof(float)) return false;
  values.resize(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return true;
}

// The page's #facet-result, its entities decoded.
std::string page_result(const std::string& dom) {
  const std::string open = "<pre id=\"facet-result\">";
  const size_t a = dom.find(open), b = a == std::string::npos ? a : dom.find("</pre>", a);
  if (b == std::string::npos) return "";
  std::string text = dom.substr(a + open.size(), b - a - open.size()), out;
  for (size_t i = 0; i < text.size(); ++i) {
    const std::pair<const char*, char> entities[] = {{"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&amp;", '&'}};
    bool decoded = false;
    for (const auto& [name, c] : entities)
      if (text.compare(i, std::strlen(name), name) == 0) {
        out += c;
        i += std::strlen(name) - 1;
        decoded = true;
        break;
      }
    if (!decoded) out += text[i];
  }
  return out;
}

// Material pass `pass` of the page: its shader, light uniforms and textures (the G-buffer's
// six images as the pass reads them, the lights, then the material's own).
json page_pass(const Material& m, const GBuffer& g, size_t pass, const std::string& fragment) {
  json textures = json::array();
  for (int i = 0; i < GBuffer::kImages; ++i) {
    json t = {{"name", GBuffer::sampler(i)}, {"width", g.width}, {"height", g.height},
              {"data", base64(i == GBuffer::Position ? g.pass_position(pass) : g.images[size_t(i)])}};
    if (i == GBuffer::Visibility) t["layers"] = g.layers;
    textures.push_back(t);
  }
  const LightTexture lights = light_texture(g);
  textures.push_back({{"name", "facet_light_texture"}, {"width", lights.width}, {"height", lights.height},
                      {"data", base64(lights.rgba)}});
  for (const auto& c : image_calls(compile(m)))
    textures.push_back({{"name", "facet_texture_" + c.name}, {"width", c.texels->width},
                        {"height", c.texels->height}, {"data", base64(c.texels->rgba)}});
  json uniforms = json::array();
  for (const auto& [name, values] : shading_uniforms(g)) uniforms.push_back({name, values});
  return {{"what", "the ES 3.00 shader of \"" + m.name + "\""}, {"fragment", fragment}, {"uniforms", uniforms},
          {"textures", textures}};
}

// A job's image from the page's images, one a pass (rows bottom-up): they add up.
void add_passes(const json& images, const RenderJob& job, size_t passes, RenderOutcome& out) {
  if (!images.is_array() || images.size() != passes) {
    out.error = fmt::format("the page gave {} images for {} passes", images.size(), passes);
    return;
  }
  const size_t w = size_t(job.width), n = w * size_t(job.height);
  out.image = Image(job.width, job.height);
  out.alpha.assign(n, 0);
  for (size_t k = 0; k < passes; ++k) {
    std::vector<float> px;
    if (!images[k].is_string() || !unbase64(images[k].get<std::string>(), px) || px.size() != n * 4) {
      out.error = fmt::format("pass {}: the page's pixels are not {}×{} RGBA floats", k, job.width, job.height);
      return;
    }
    for (size_t i = 0; i < n; ++i) {  // GL rows run bottom-up, facet's top-down
      const size_t x = i % w, y = size_t(job.height) - 1 - i / w;
      float* dst = out.image.at(int(x), int(y));
      for (size_t c = 0; c < 3; ++c) dst[c] += px[i * 4 + c];
      out.alpha[y * w + x] = std::max(out.alpha[y * w + x], px[i * 4 + 3]);
    }
  }
  out.ok = true;
}

// Pages hold the jobs' G-buffers as base64 and give back their images so: up to this
// many bytes of both a page (one Chromium start each, 3.7 s on this machine, more than a
// job's drawing; a 512² sweep gives back 5.6 MB).
const size_t kPageBytes = size_t(48) << 20;

class WebglRenderer : public Renderer {
 public:
  explicit WebglRenderer(const RendererInfo& info) : info_(info), chromium_(find_program("chromium")) {
    if (!chromium_.empty()) {
      std::string v = run_process({chromium_, "--version"}).output;
      description_ = v.substr(0, v.find('\n')) + ", WebGL2 through ANGLE on SwiftShader";
    }
  }
  const RendererInfo& info() const override { return info_; }
  std::string unavailable() const override {
    if (chromium_.empty()) return "chromium: not found on PATH (Debian's chromium package)";
    return gl_.ok() ? "" : "the G-buffer needs OpenGL: " + gl_.error();
  }
  std::string description() const override { return description_; }

  // The jobs' G-buffers cast one after another, gathered into pages of up to
  // kPageBytes, each page one Chromium run.
  std::vector<RenderOutcome> render(const std::vector<RenderJob>& jobs, const RenderProgress& progress) override {
    if (std::string why = unavailable(); !why.empty()) return failed_renders(jobs.size(), why);
    std::vector<RenderOutcome> out(jobs.size());
    std::vector<size_t> passes(jobs.size(), 0);
    Pages pages{*this, jobs, passes, out, progress};
    for (size_t i = 0; i < jobs.size(); ++i) {
      const auto start = std::chrono::steady_clock::now();
      json job = job_data(jobs[i], passes[i], out[i].error);
      out[i].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!job.is_null()) pages.add(i, std::move(job));
      else if (progress.finished) progress.finished(i);
    }
    pages.flush();
    return out;
  }

  // Each material's ES 3.00 sweep harness (targets.h, glsl_sweep_source()) drawn on
  // grid × grid pixels (at most 512), its raw values counted.
  std::vector<SweepCount> sweep(const std::vector<SweepJob>& jobs, const SweepSettings& settings) override {
    if (std::string why = unavailable(); !why.empty()) return failed_sweeps(jobs.size(), info_.name, why);
    const int grid = std::min(settings.grid, 512);
    std::vector<RenderJob> draws(jobs.size());
    std::vector<RenderOutcome> out(jobs.size());
    std::vector<size_t> passes(jobs.size(), 1);
    const RenderProgress quiet;
    Pages pages{*this, draws, passes, out, quiet};
    for (size_t i = 0; i < jobs.size(); ++i) {
      draws[i].material = jobs[i].material;
      draws[i].scene.name = "sweep";
      draws[i].width = draws[i].height = grid;
      draws[i].workdir = settings.workdir;
      const std::string source = jobs[i].source.empty() ? glsl_sweep_source(jobs[i].material, Target::Essl) : jobs[i].source;
      json pass = {{"what", "the ES 3.00 sweep of \"" + jobs[i].material.name + "\""}, {"fragment", source},
                   {"uniforms", json::array({json::array({"facet_resolution", {grid, grid}})})},
                   {"textures", json::array()}};
      pages.add(i, {{"width", grid}, {"height", grid}, {"passes", json::array({pass})}});
    }
    pages.flush();
    std::vector<SweepCount> counts(jobs.size());
    for (size_t i = 0; i < jobs.size(); ++i) {
      counts[i].target = info_.name;
      count_sweep_outcome(counts[i], out[i]);
    }
    return counts;
  }

 private:
  // Jobs gathered into pages of up to kPageBytes of data in and out, each page one Chromium run.
  struct Pages {
    WebglRenderer& renderer;
    const std::vector<RenderJob>& jobs;
    const std::vector<size_t>& passes;
    std::vector<RenderOutcome>& out;
    const RenderProgress& progress;
    std::vector<size_t> batch = {};
    json data = json::array();
    size_t bytes = 0;
    // The job's data and the base64 images it gives back (4/3 of 16 bytes a pixel a pass) count.
    void add(size_t i, json job) {
      const size_t pixels = job["width"].get<size_t>() * job["height"].get<size_t>();
      bytes += job.dump().size() + pixels * 64 / 3 * job["passes"].size();
      data.push_back(std::move(job));
      batch.push_back(i);
      if (bytes >= kPageBytes) flush();
    }
    void flush() {
      if (batch.empty()) return;
      renderer.run_page(jobs, batch, passes, data, out);
      for (size_t k : batch)
        if (progress.finished) progress.finished(k);
      batch.clear();
      data = json::array();
      bytes = 0;
    }
  };
  json job_data(const RenderJob& job, size_t& passes, std::string& error);
  void run_page(const std::vector<RenderJob>& jobs, const std::vector<size_t>& batch, const std::vector<size_t>& passes,
                const json& data, std::vector<RenderOutcome>& out);
  std::string chromium_dom(const RenderJob& first, const std::string& html, std::string& log, std::string& error);

  const RendererInfo& info_;
  std::string chromium_, description_;
  GlRenderer gl_;
};

// A job's page data, every material pass's shader and G-buffer (cast once for them all): null
// with `error` set when it cannot.
json WebglRenderer::job_data(const RenderJob& job, size_t& count, std::string& error) {
  std::vector<const Material*> passes;
  try {
    passes = material_passes(job);
  } catch (const std::exception& e) {
    error = e.what();
    return nullptr;
  }
  if (!job.code_override.empty() && passes.size() != 1) {
    error = "code_override needs a scene with one material";
    return nullptr;
  }
  json data = {{"width", job.width}, {"height", job.height}, {"passes", json::array()}};
  const GBufferOutcome g = cast_gbuffer(gl_, job);  // once for every pass
  if (!g.ok) {
    error = "the G-buffer: " + g.error;
    return nullptr;
  }
  for (size_t k = 0; k < passes.size(); ++k) {
    std::string fragment = job.code_override.empty() ? glsl_gbuffer_shading_source(*passes[k], Target::Essl)
                                                     : job.code_override;
    if (!job.workdir.empty()) {
      fs::create_directories(job.workdir);
      const std::string base = pass_name(job, k, passes.size(), passes[k]->name);
      write_file_atomic((fs::path(job.workdir) / (base + ".webgl.frag")).string(), fragment);
    }
    data["passes"].push_back(page_pass(*passes[k], g.gbuffer, k, fragment));
  }
  count = passes.size();
  return data;
}

// One page of the batch's jobs through Chromium; each job's outcome from its line of the result.
void WebglRenderer::run_page(const std::vector<RenderJob>& jobs, const std::vector<size_t>& batch,
                             const std::vector<size_t>& passes, const json& data, std::vector<RenderOutcome>& out) {
  const auto start = std::chrono::steady_clock::now();
  std::string text = json{{"vertex", kVertexShader}, {"jobs", data}}.dump();
  for (size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  std::string log, error;
  const std::string dom = chromium_dom(jobs[batch[0]], render_harness("webgl.html", {{"data", text}}), log, error);
  const std::string result = dom.empty() ? "" : page_result(dom);
  std::vector<std::string> lines;
  for (size_t a = 0, b; a < result.size(); a = b + 1) {
    b = std::min(result.find('\n', a), result.size());
    lines.push_back(result.substr(a, b - a));
  }
  if (error.empty() && (lines.empty() || lines[0].rfind("OK ", 0) != 0))
    error = !lines.empty() && lines[0].rfind("ERROR ", 0) == 0 ? result.substr(6) : "Chromium gave no result: " + log;
  else if (error.empty() && lines.size() != batch.size() + 1)
    error = fmt::format("the page gave {} results for {} jobs", lines.size() - 1, batch.size());
  if (error.empty()) description_ = "Chromium WebGL2 on " + lines[0].substr(3);
  const double each = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / double(batch.size());
  for (size_t k = 0; k < batch.size(); ++k) {
    RenderOutcome& o = out[batch[k]];
    o.log = log;
    o.seconds += each;
    if (!error.empty()) {
      o.error = error;
      continue;
    }
    const json r = json::parse(lines[k + 1], nullptr, false);
    if (r.is_object() && r.contains("error")) o.error = r["error"].get<std::string>();
    else if (r.is_object() && r.contains("images")) add_passes(r["images"], jobs[batch[k]], passes[batch[k]], o);
    else o.error = "the page's result for this job is not JSON";
  }
}

// Chromium on the page: its DOM after the script ran, or "" with `error` set. The page
// (megabytes of base64) and the DOM live in a folder of their own, removed after the run;
// the job's workdir keeps the shaders (.webgl.frag).
std::string WebglRenderer::chromium_dom(const RenderJob& first, const std::string& html, std::string& log,
                                        std::string& error) {
  static int runs = 0;
  const fs::path folder = fs::path(private_work_folder()) / fmt::format("webgl-{}", runs++);
  fs::create_directories(folder);
  const fs::path file = folder / (job_name(first) + ".html"), dom = folder / "dom.html";
  write_file_atomic(file.string(), html);
  // stdout (the DOM) to a file; stderr (Chromium's own messages) is the log.
  ProcessResult r = run_process({"timeout", "600", "sh", "-c", "exec \"$0\" \"$@\" > \"$FACET_DOM\"", chromium_,
                                 "--headless=new", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                                 "--no-sandbox", "--no-first-run", "--user-data-dir=" + (folder / "profile").string(),
                                 "--dump-dom", "file://" + fs::absolute(file).string()},
                                "", {"FACET_DOM=" + dom.string()});
  log = r.output;
  std::string text;
  if (r.exit_code != 0) error = fmt::format("chromium exited with {}: {}", r.exit_code, r.output.substr(0, 2000));
  else text = read_file(dom.string());
  std::error_code ec;
  fs::remove_all(folder, ec);
  return text;
}

}  // namespace

std::unique_ptr<Renderer> make_webgl_renderer(const RendererInfo& info, const RendererSettings&) {
  return std::make_unique<WebglRenderer>(info);
}

}  // namespace facet
