// facet_mesh_bench: POV-Ray on meshes of growing size, the way a user runs it.
//
// For each size (about 2 k … 2 M triangles: an icosphere, a torus and a creased
// box, scene/shapes.h) and each of three materials — native (Lambert +
// Blinn–Phong: POV-Ray's own finish), isotropic (Oren–Nayar + GGX) and
// anisotropic (Lambert + Ward), both on function pigments — it writes the scene
// as a GLB with the material, then runs, each as its own process and measured by
// wait4 (wall time, peak resident memory):
//   facet import-gltf bench.glb -o bench.json
//   facet generate --target pov --scene bench.json -o bench.pov
//   povray +Ibench.pov +W640 +H480 …        (POV-Ray's own parse and trace times)
// POV-Ray runs --repeats times (3 unless told), the materials of a size taking
// turns, and each time is the least of its runs: on a shared 2-core machine one
// run's times vary by ±20 %, and the least is the one least disturbed.
// It prints one row per size and material: the times, the files' sizes, the
// peak memory, the ratio of POV-Ray's time to the native route's on the same
// mesh, and the growth exponent from the previous size, d log(time) / d log(n).
// Figures, not assertions: it only fails when a step fails. `--no-povray` writes
// the scenes and stops there (the 128 k validation test reads them).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "core/io.h"
#include "docs/chart.h"
#include "scene/gltf.h"
#include "scene/shapes.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Measured {
  int exit_code = -1;
  double seconds = 0;
  double peak_mb = 0;
  std::string output;
};

// Runs argv in `cwd`, output to a file, and measures it with wait4.
Measured run(const std::vector<std::string>& argv, const fs::path& cwd) {
  const fs::path log = cwd / "run.log";
  auto start = std::chrono::steady_clock::now();
  pid_t pid = fork();
  if (pid == 0) {
    if (chdir(cwd.c_str()) != 0) _exit(126);
    FILE* f = std::freopen(log.c_str(), "w", stdout);
    if (!f || dup2(fileno(stdout), 2) < 0) _exit(126);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    _exit(127);
  }
  Measured m;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  m.peak_mb = double(usage.ru_maxrss) / 1024;
  m.output = facet::read_file(log.string());
  return m;
}

// POV-Ray's "Parse Time: … (6.161 seconds)" and "Trace Time: …".
double pov_time(const std::string& output, const std::string& what) {
  std::smatch m;
  std::regex re(what + " Time:[^(]*\\(([0-9.]+) seconds\\)");
  return std::regex_search(output, m, re) ? std::stod(m[1]) : -1;
}

double megabytes(const fs::path& p) { return fs::exists(p) ? double(fs::file_size(p)) / 1e6 : 0; }

struct Row {
  size_t triangles = 0;
  std::string material;
  double import_s = 0, import_mb = 0, generate_s = 0, generate_mb = 0;
  double glb_mb = 0, json_kb = 0, pov_mb = 0, data_mb = 0;
  double parse_s = 0, trace_s = 0, pov_peak_mb = 0;
  std::string error;
  double pov_s() const { return parse_s + trace_s; }
};

struct Options {
  std::vector<size_t> sizes = {2048, 8192, 32768, 131072, 524288, 2097152};
  std::vector<std::string> materials = {"native", "isotropic", "anisotropic", "isotropic-fast"};
  fs::path out = "out/mesh_bench", facet, markdown, plot;
  int width = 640, height = 480;
  int repeats = 3;
  bool povray = true;  // --no-povray: the scenes only (GLB, facet scene, generated POV-Ray files)
};

// "isotropic-fast" is the isotropic material through --pov-route fast (slope tables).
facet::Material bench_material(std::string kind) {
  if (kind == "isotropic-fast") kind = "isotropic";
  json j;
  if (kind == "native")
    j = {{"name", "native"},
         {"diffuse", {{"model", "lambert"}, {"color", {0.55, 0.42, 0.32}}}},
         {"specular", {{"model", "blinn_phong"}, {"n", 40}}}};
  else if (kind == "isotropic")
    j = {{"name", "isotropic"},
         {"diffuse", {{"model", "oren_nayar"}, {"color", {0.55, 0.42, 0.32}}, {"sigma", 0.4}}},
         {"specular", {{"model", "ggx"}, {"alpha", 0.2}}}};
  else
    j = {{"name", "anisotropic"},
         {"diffuse", {{"model", "lambert"}, {"color", {0.25, 0.25, 0.28}}}},
         {"specular", {{"model", "ward"}, {"color", {0.8, 0.75, 0.7}}, {"alpha_x", 0.12}, {"alpha_y", 0.35}}}};
  return facet::parse_material(j, kind + ".json");
}

fs::path folder(const Options& o, size_t triangles, const std::string& kind) {
  return o.out / fmt::format("{}_{}", triangles, kind);
}

// Writes each material's GLB of the size-n scene in a child process, so that this
// one stays small: a child's peak memory as wait4 reports it includes what it
// inherited from its parent before exec. Returns the scene's triangle count.
size_t write_glbs(size_t n, const Options& o) {
  int pipefd[2];
  if (pipe(pipefd) != 0) return 0;
  pid_t pid = fork();
  if (pid == 0) {
    close(pipefd[0]);
    facet::Scene scene = facet::mesh_bench_scene(n);
    size_t triangles = 0;
    for (const auto& obj : scene.objects) triangles += obj.mesh->triangles.size();
    for (const auto& kind : o.materials) {
      fs::create_directories(folder(o, triangles, kind));
      const facet::Material m = bench_material(kind);
      std::vector<std::string> notes;
      facet::export_gltf(scene, &m, (folder(o, triangles, kind) / "bench.glb").string(), notes);
    }
    ssize_t written = write(pipefd[1], &triangles, sizeof triangles);
    _exit(written == ssize_t(sizeof triangles) ? 0 : 1);
  }
  close(pipefd[1]);
  size_t triangles = 0;
  if (read(pipefd[0], &triangles, sizeof triangles) != ssize_t(sizeof triangles)) triangles = 0;
  close(pipefd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return triangles;
}

Row measure(size_t triangles, const std::string& kind, const Options& o) {
  Row r;
  r.triangles = triangles;
  r.material = kind;
  const fs::path dir = folder(o, triangles, kind);
  r.glb_mb = megabytes(dir / "bench.glb");
  Measured imp = run({o.facet.string(), "import-gltf", "bench.glb", "-o", "bench.json"}, dir);
  r.import_s = imp.seconds, r.import_mb = imp.peak_mb;
  r.json_kb = megabytes(dir / "bench.json") * 1e3;
  if (imp.exit_code != 0) return r.error = "import-gltf: " + imp.output, r;
  Measured gen = run({o.facet.string(), "generate", "--target", "pov", "--scene", "bench.json", "--pov-route",
                      kind == "isotropic-fast" ? "fast" : "auto", "-o", "bench.pov"},
                     dir);
  r.generate_s = gen.seconds, r.generate_mb = gen.peak_mb;
  if (gen.exit_code != 0) return r.error = "generate: " + gen.output, r;
  r.pov_mb = megabytes(dir / "bench.pov");
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".inc") r.pov_mb += megabytes(e.path());  // the meshes' lists
    if (e.path().extension() == ".ppm") r.data_mb += megabytes(e.path());
  }
  return r;
}

// One POV-Ray run of the row's scene; its times count where they are the least so far.
void render(Row& r, const Options& o) {
  const fs::path dir = folder(o, r.triangles, r.material);
  Measured pov = run({"povray", "+Ibench.pov", "+Obench.png", fmt::format("+W{}", o.width),
                      fmt::format("+H{}", o.height), "-A", "+FN16", "File_Gamma=1.0", "-D"},
                     dir);
  const double parse = pov_time(pov.output, "Parse"), trace = pov_time(pov.output, "Trace");
  if (pov.exit_code != 0 || parse < 0) {
    r.error = "povray: " + pov.output.substr(0, 2000);
    return;
  }
  const bool first = r.parse_s == 0 && r.trace_s == 0;
  r.parse_s = first ? parse : std::min(r.parse_s, parse);
  r.trace_s = first ? trace : std::min(r.trace_s, trace);
  r.pov_peak_mb = std::max(r.pov_peak_mb, pov.peak_mb);
}

double exponent(double t1, double t0, double n1, double n0) {
  return t1 > 0 && t0 > 0 ? std::log(t1 / t0) / std::log(n1 / n0) : NAN;
}

const Row* find(const std::vector<Row>& rows, size_t n, const std::string& kind) {
  for (const auto& r : rows)
    if (r.triangles == n && r.material == kind) return &r;
  return nullptr;
}

std::string table(const std::vector<Row>& rows) {
  std::string out =
      "| triangles | material | import s / MB | generate s / MB | .glb MB | .json kB | .pov + .inc MB | data MB | "
      "POV-Ray parse s | trace s | POV-Ray peak MB | ÷ native | exponent (parse, memory) |\n"
      "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : rows) {
    const Row* native = find(rows, r.triangles, "native");
    const Row* prev = nullptr;
    for (const auto& q : rows)
      if (q.material == r.material && q.triangles < r.triangles && (!prev || q.triangles > prev->triangles)) prev = &q;
    std::string ratio = native && native->pov_s() > 0 ? fmt::format("{:.2f}", r.pov_s() / native->pov_s()) : "";
    std::string growth = prev ? fmt::format("{:.2f}, {:.2f}", exponent(r.parse_s, prev->parse_s, r.triangles, prev->triangles),
                                            exponent(r.pov_peak_mb, prev->pov_peak_mb, r.triangles, prev->triangles))
                              : "";
    if (!r.error.empty()) {
      out += fmt::format("| {} | {} | failed: {} |\n", r.triangles, r.material, r.error.substr(0, 120));
      continue;
    }
    out += fmt::format("| {} | {} | {:.2f} / {:.0f} | {:.2f} / {:.0f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.2f} | "
                       "{:.2f} | {:.0f} | {} | {} |\n",
                       r.triangles, r.material, r.import_s, r.import_mb, r.generate_s, r.generate_mb, r.glb_mb,
                       r.json_kb, r.pov_mb, r.data_mb, r.parse_s, r.trace_s, r.pov_peak_mb, ratio, growth);
  }
  return out;
}

// Between 32 k and the largest size: the exponents the issue bounds.
std::string summary(const std::vector<Row>& rows) {
  std::string out;
  for (const std::string kind : {"native", "isotropic", "anisotropic", "isotropic-fast"}) {
    const Row *lo = nullptr, *hi = nullptr;
    for (const auto& r : rows)
      if (r.material == kind && r.error.empty() && r.triangles >= 30000) {
        if (!lo || r.triangles < lo->triangles) lo = &r;
        if (!hi || r.triangles > hi->triangles) hi = &r;
      }
    if (!lo || lo == hi) continue;
    out += fmt::format("{}: {} → {} triangles: growth exponent of POV-Ray's parse time {:.2f}, of its peak memory "
                       "{:.2f}, of generate's time {:.2f}\n",
                       kind, lo->triangles, hi->triangles, exponent(hi->parse_s, lo->parse_s, hi->triangles, lo->triangles),
                       exponent(hi->pov_peak_mb, lo->pov_peak_mb, hi->triangles, lo->triangles),
                       exponent(hi->generate_s, lo->generate_s, hi->triangles, lo->triangles));
  }
  return out;
}

void plot(const std::vector<Row>& rows, const fs::path& path) {
  const facet::Color colors[] = {facet::Color::hex(0x1f77b4), facet::Color::hex(0xd62728), facet::Color::hex(0x2ca02c),
                                 facet::Color::hex(0x9467bd)};
  facet::LogLogChart time{"POV-Ray parse time against mesh size", "triangles", "seconds", {}, 1, 560, 380};
  facet::LogLogChart memory{"POV-Ray peak memory against mesh size", "triangles", "MB", {}, 1, 560, 380};
  int c = 0;
  for (const std::string kind : {"native", "isotropic", "anisotropic", "isotropic-fast"}) {
    facet::ChartSeries t{kind, colors[c], {}, {}, false}, m{kind, colors[c++], {}, {}, false};
    for (const auto& r : rows)
      if (r.material == kind && r.error.empty()) {
        t.x.push_back(double(r.triangles)), t.y.push_back(r.parse_s);
        m.x.push_back(double(r.triangles)), m.y.push_back(r.pov_peak_mb);
      }
    time.series.push_back(t), memory.series.push_back(m);
  }
  // Two files: PLOT_parse.svg and PLOT_memory.svg.
  const fs::path stem = path.parent_path() / path.stem();
  facet::write_file_atomic(stem.string() + "_parse.svg", facet::draw_loglog(time).svg());
  facet::write_file_atomic(stem.string() + "_memory.svg", facet::draw_loglog(memory).svg());
}

std::optional<Options> parse_args(int argc, char** argv) {
  Options o;
  o.facet = fs::path(FACET_BINARY);
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--sizes") {
      o.sizes.clear();
      std::string list = next();
      for (size_t p = 0; p < list.size();) {
        size_t e = list.find(',', p);
        std::string s = list.substr(p, e == std::string::npos ? std::string::npos : e - p);
        double k = s.back() == 'M' ? 1048576 : s.back() == 'k' ? 1024 : 1;
        o.sizes.push_back(size_t(std::stod(s) * k));
        p = e == std::string::npos ? list.size() : e + 1;
      }
    } else if (a == "--materials") {
      o.materials.clear();
      std::string list = next();
      for (size_t p = 0; p <= list.size();) {
        size_t e = std::min(list.find(',', p), list.size());
        o.materials.push_back(list.substr(p, e - p));
        p = e + 1;
      }
    } else if (a == "--out") o.out = next();
    else if (a == "--facet") o.facet = next();
    else if (a == "--repeats") o.repeats = std::max(1, std::stoi(next()));
    else if (a == "--no-povray") o.povray = false;
    else if (a == "--markdown") o.markdown = next();
    else if (a == "--plot") o.plot = next();
    else if (a == "--size") {
      std::string s = next();
      o.width = std::stoi(s.substr(0, s.find('x')));
      o.height = std::stoi(s.substr(s.find('x') + 1));
    } else {
      std::cerr << "usage: facet_mesh_bench [--sizes 2k,8k,32k,128k,512k,2M] [--materials native,isotropic,anisotropic,isotropic-fast]\n"
                   "                        [--size 640x480] [--repeats 3] [--no-povray] [--out DIR] [--markdown FILE.md] [--plot STEM (STEM_parse.svg, STEM_memory.svg)] [--facet PATH]\n";
      return std::nullopt;
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::optional<Options> o = parse_args(argc, argv);
  if (!o) return 2;
  o->out = fs::absolute(o->out);
  fs::create_directories(o->out);
  std::vector<Row> rows;
  bool failed = false;
  for (size_t n : o->sizes) {
    const size_t triangles = write_glbs(n, *o);
    if (triangles == 0) {
      std::cerr << "facet_mesh_bench: could not write the scenes of " << n << " triangles\n";
      return 1;
    }
    std::vector<Row> size_rows;
    for (const auto& kind : o->materials) size_rows.push_back(measure(triangles, kind, *o));
    for (int k = 0; o->povray && k < o->repeats; ++k)  // the materials take turns
      for (auto& r : size_rows)
        if (r.error.empty()) render(r, *o);
    for (const auto& r : size_rows) {
      std::cerr << fmt::format("{:>8} triangles, {:<14}: generate {:.2f} s, POV-Ray parse {:.2f} s, trace {:.2f} s, "
                               "peak {:.0f} MB{}\n",
                               r.triangles, r.material, r.generate_s, r.parse_s, r.trace_s, r.pov_peak_mb,
                               r.error.empty() ? "" : " — " + r.error.substr(0, 300));
      failed |= !r.error.empty();
      rows.push_back(r);
    }
  }
  std::string md = table(rows) + "\n" +
                   fmt::format("POV-Ray's parse and trace times: each the least of {} runs, the materials of a size "
                               "taking turns.\n",
                               o->repeats) +
                   summary(rows);
  std::cout << md;
  if (!o->markdown.empty()) facet::write_file_atomic(o->markdown.string(), md);
  if (!o->plot.empty()) plot(rows, o->plot);
  return failed ? 1 : 0;
}
