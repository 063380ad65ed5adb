// facet_many_bench: the renderers on scenes of many objects and many lights.
//
// For each number of objects (100, 1,000, 10,000 unless told) and of lights (1, 8, 64,
// 1,000) it draws scene/shapes.h's many_objects_scene() — a floor and a grid of spheres,
// small squares and small meshes under point, spot and directional lights, four example
// materials (lambert, blinn_phong, oren_nayar, ggx, unless told) — with each renderer asked for
// (reference, glsl, vulkan, vulkan-hlsl, webgl, wgpu unless told), each run in a child
// process of its own that builds the scene, starts the renderer and renders: the time is
// the child's render() call (its device, browser or Python start included), the peak
// memory is what wait4 reports for the child (the largest of it and the processes it
// ran). A run past --timeout seconds is stopped and reported so. Figures, not assertions:
// it fails only when a render fails.
//
//   facet_many_bench [--objects 100,1000,10000] [--lights 1,8,64,1000] [--renderers LIST]
//                    [--size 160x120] [--timeout 600] [--skip OBJECTSxLIGHTS:RENDERER,…]
//                    [--materials lambert,blinn_phong,…] [--out DIR] [--python PY] [--markdown FILE.md]
//   facet_many_bench --write-scene OBJECTSxLIGHTS FILE.json [--materials …]   (the scene as a file: the tests
//                    validate it)
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "catalog/material.h"
#include "core/io.h"
#include "renderers/renderer.h"
#include "scene/scene.h"
#include "scene/shapes.h"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = FACET_SOURCE_DIR;

struct Options {
  std::vector<size_t> objects = {100, 1000, 10000}, lights = {1, 8, 64, 1000};
  std::vector<std::string> renderers = {"reference", "glsl", "vulkan", "vulkan-hlsl", "webgl", "wgpu"};
  std::vector<std::string> skip;  // "OBJECTSxLIGHTS:RENDERER"
  std::vector<std::string> materials = {"lambert", "blinn_phong", "oren_nayar", "ggx"};  // examples/materials/
  std::string write_scene, scene_file;  // --write-scene OBJECTSxLIGHTS FILE
  int width = 160, height = 120;
  double timeout = 600;
  fs::path out = "out/many_bench", markdown;
  std::string python;
};

std::vector<facet::Material> bench_materials(const Options& o) {
  std::vector<facet::Material> out;
  for (const std::string& name : o.materials)
    out.push_back(facet::load_material((kSource / "examples" / "materials" / (name + ".json")).string()));
  return out;
}

facet::Scene bench_scene(const Options& o, size_t objects, size_t lights) {
  return facet::many_objects_scene(objects, lights, bench_materials(o));
}

struct Row {
  size_t objects = 0, lights = 0;
  std::string renderer;
  double seconds = 0, peak_mb = 0;
  std::string status;  // "" when it rendered
};

// What the child writes back through its pipe: the render's seconds and its error, if any.
struct ChildResult {
  double seconds = -1;
  char error[512] = {};
};

[[noreturn]] void child(const Options& o, const Row& r, int fd) {
  setpgid(0, 0);  // a group of its own: a timeout stops its browser or Python too
  ChildResult res;
  try {
    facet::RenderJob job;
    job.scene = bench_scene(o, r.objects, r.lights);
    job.width = o.width;
    job.height = o.height;
    job.workdir = (o.out / fmt::format("{}x{}_{}", r.objects, r.lights, r.renderer)).string();
    facet::RendererSettings settings;
    settings.python = o.python;
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<facet::Renderer> renderer = facet::make_renderer(r.renderer, settings);
    facet::RenderOutcome out = renderer->render({job}).at(0);
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!out.ok) std::snprintf(res.error, sizeof res.error, "%s", out.error.c_str());
    else {
      fs::create_directories(job.workdir);
      facet::write_pfm((fs::path(job.workdir) / "image.pfm").string(), out.image);
    }
  } catch (const std::exception& e) {
    std::snprintf(res.error, sizeof res.error, "%s", e.what());
  }
  const bool written = write(fd, &res, sizeof res) == ssize_t(sizeof res);
  _exit(written ? 0 : 1);
}

// One run in a child process, measured by wait4; stopped (its whole group) after o.timeout.
void measure(const Options& o, Row& r) {
  int pipefd[2];
  if (pipe(pipefd) != 0) {
    r.status = "no pipe";
    return;
  }
  std::cout.flush();
  const pid_t pid = fork();
  if (pid == 0) {
    close(pipefd[0]);
    child(o, r, pipefd[1]);
  }
  close(pipefd[1]);
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  rusage usage{};
  bool stopped = false;
  while (wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > o.timeout && !stopped) {
      kill(-pid, SIGKILL);
      stopped = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ChildResult res;
  const bool read_back = read(pipefd[0], &res, sizeof res) == ssize_t(sizeof res);
  close(pipefd[0]);
  r.peak_mb = double(usage.ru_maxrss) / 1024;
  if (stopped) r.status = fmt::format("stopped after {:.0f} s", o.timeout);
  else if (!read_back) r.status = "the child wrote no result";
  else if (res.error[0]) r.status = std::string("failed: ") + res.error;
  r.seconds = read_back ? res.seconds : std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string table(const std::vector<Row>& rows, const Options& o) {
  std::string out = fmt::format("| objects | lights | {} |\n|---:|---:|", fmt::join(o.renderers, " | "));
  for (size_t i = 0; i < o.renderers.size(); ++i) out += "---:|";
  out += "\n";
  for (size_t n : o.objects)
    for (size_t l : o.lights) {
      out += fmt::format("| {} | {} |", n, l);
      for (const auto& name : o.renderers)
        for (const Row& r : rows)
          if (r.objects == n && r.lights == l && r.renderer == name)
            out += r.status.empty() ? fmt::format(" {:.2f} s / {:.0f} MB |", r.seconds, r.peak_mb)
                   : r.status == "skipped" ? " skipped |"
                                           : fmt::format(" {} |", r.status.substr(0, 60));
      out += "\n";
    }
  return out;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  for (size_t p = 0; p <= list.size();) {
    size_t e = std::min(list.find(',', p), list.size());
    if (e > p) out.push_back(list.substr(p, e - p));
    p = e + 1;
  }
  return out;
}

std::vector<size_t> numbers(const std::string& list) {
  std::vector<size_t> out;
  for (const auto& s : split(list)) out.push_back(size_t(std::stoul(s)));
  return out;
}

bool parse_size(const std::string& s, size_t& a, size_t& b) {
  const size_t x = s.find('x');
  if (x == std::string::npos) return false;
  a = size_t(std::stoul(s.substr(0, x)));
  b = size_t(std::stoul(s.substr(x + 1)));
  return true;
}

int write_scene(const Options& o) {
  size_t objects = 0, lights = 0;
  if (!parse_size(o.write_scene, objects, lights) || o.scene_file.empty()) {
    std::cerr << "facet_many_bench: --write-scene takes OBJECTSxLIGHTS and a file, e.g. 300x64 many.json\n";
    return 2;
  }
  facet::write_file_atomic(o.scene_file, facet::to_json(bench_scene(o, objects, lights)).dump(1) + "\n");
  return 0;
}

std::optional<Options> parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    size_t w = 0, h = 0;
    if (a == "--objects") o.objects = numbers(next());
    else if (a == "--lights") o.lights = numbers(next());
    else if (a == "--renderers") o.renderers = split(next());
    else if (a == "--skip") o.skip = split(next());
    else if (a == "--timeout") o.timeout = std::stod(next());
    else if (a == "--out") o.out = next();
    else if (a == "--python") o.python = next();
    else if (a == "--markdown") o.markdown = next();
    else if (a == "--materials") o.materials = split(next());
    else if (a == "--write-scene") o.write_scene = next(), o.scene_file = next();
    else if (a == "--size" && parse_size(next(), w, h)) o.width = int(w), o.height = int(h);
    else {
      std::cerr << "usage: facet_many_bench [--objects 100,1000,10000] [--lights 1,8,64,1000]\n"
                   "         [--renderers reference,glsl,vulkan,vulkan-hlsl,webgl,wgpu] [--size 160x120] [--timeout 600]\n"
                   "         [--skip OBJECTSxLIGHTS:RENDERER,...] [--materials lambert,blinn_phong,oren_nayar,ggx]\n"
                   "         [--out DIR] [--python PY] [--markdown FILE.md]\n"
                   "       facet_many_bench --write-scene OBJECTSxLIGHTS FILE.json [--materials ...]\n";
      return std::nullopt;
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::optional<Options> o = parse_args(argc, argv);
  if (!o) return 2;
  if (!o->write_scene.empty()) return write_scene(*o);
  o->out = fs::absolute(o->out);
  fs::create_directories(o->out);
  std::vector<Row> rows;
  bool failed = false;
  for (size_t n : o->objects)
    for (size_t l : o->lights)
      for (const auto& name : o->renderers) {
        Row r;
        r.objects = n, r.lights = l, r.renderer = name;
        const std::string key = fmt::format("{}x{}:{}", n, l, name);
        if (std::find(o->skip.begin(), o->skip.end(), key) != o->skip.end()) r.status = "skipped";
        else measure(*o, r);
        failed |= !r.status.empty() && r.status != "skipped";
        std::cerr << fmt::format("{:>6} objects, {:>5} lights, {:<12} {:8.2f} s {:6.0f} MB {}\n", n, l, name, r.seconds,
                                 r.peak_mb, r.status.substr(0, 300));
        rows.push_back(r);
      }
  const std::string md = table(rows, *o) +
                         fmt::format("\n{}×{} pixels; each cell: the render's wall time (its renderer's start included) "
                                     "and the peak memory of its process.\n",
                                     o->width, o->height);
  std::cout << md;
  if (!o->markdown.empty()) facet::write_file_atomic(o->markdown.string(), md);
  return failed ? 1 : 0;
}
