// facet generate: generate GLSL, HLSL, OSL or POV-Ray code from a material file.
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "cli/command.h"
#include "core/io.h"
#include "scene/scene.h"
#include "targets/targets.h"

using nlohmann::json;
namespace fs = std::filesystem;

namespace facet::cli {
namespace {

struct GenerateArgs {
  std::string material;
  std::string target = "glsl";
  std::string scene;
  std::string output;
  std::string pov_route = "auto";
  bool library = false;
  bool json = false;  // --json: print what was generated as one JSON object
};

// The files beside the scene first, the scene last: a scene is never left reading a missing
// file; on a failure the side files written are removed.
void write_outputs(const PovOutput& pov, const std::string& code, const std::string& output, bool to_stdout) {
  std::vector<std::string> written;
  try {
    for (const auto& f : pov.files) {
      const std::string path = (fs::path(output).parent_path() / f.name).string();
      write_file_atomic(path, f.write);
      written.push_back(path);
    }
    if (!to_stdout) write_file_atomic(output, code);
  } catch (...) {
    for (const auto& w : written) fs::remove(w);
    throw;
  }
}

int run_generate(const GenerateArgs& a) {
  auto target = parse_target(a.target);  // CLI11 already checked the name
  std::optional<Scene> scene;
  if (!a.scene.empty()) scene = load_scene(a.scene);
  bool whole_scene = *target == Target::Pov && !a.library;
  std::optional<Material> m = whole_scene ? load_optional_material(a.material, scene,
                                                                   "unless every object of --scene has its own")
                                          : load_optional_material(a.material, std::nullopt,
                                                                   "for --target " + a.target + (a.library ? " --library" : ""));
  if (scene) check_texture_sets(*scene, m ? &*m : nullptr);
  bool to_stdout = a.output.empty() || a.output == "-";
  const PovRoute route = *parse_pov_route(a.pov_route);  // CLI11 checked the name
  std::string code;
  PovOutput pov;
  if (whole_scene) {
    const fs::path out(to_stdout ? "facet.pov" : a.output);
    const std::string named = a.scene.empty() ? a.material : a.scene;
    try {
      pov = generate_pov_files(scene ? *scene : default_scene(), m ? &*m : nullptr, m ? a.material : a.scene, route,
                               out.stem().string());
    } catch (const std::invalid_argument& e) {  // --pov-route native where a material is not
      throw InputError({Diagnostic{named, "", e.what()}});
    }
    if (!pov.files.empty() && to_stdout)
      throw InputError({Diagnostic{named, "", "its meshes read " + pov.files.front().name +
                                                  " beside the .pov (their geometry, for POV-Ray's functions): "
                                                  "give -o FILE.pov"}});
    if (!a.json)  // the JSON carries them
      for (const auto& r : pov.plan.routes) std::cerr << "facet: " << r << "\n";
    code = std::move(pov.code);
  } else if (*target == Target::Pov) {  // --library: a textured material's images beside it
    const fs::path out(to_stdout ? "facet.inc" : a.output);
    pov = generate_pov_library(*m, a.material, route, out.stem().string());
    if (!pov.files.empty() && to_stdout)
      throw InputError({Diagnostic{a.material, "", "its library reads " + pov.files.front().name +
                                                       " beside it (a texture's texels): give -o FILE.inc"}});
    code = std::move(pov.code);
  } else {
    GenerateOptions o;
    o.target = *target;
    o.library = a.library;
    o.source = a.material;
    o.scene = scene;
    o.pov_route = route;
    code = generate(*m, o);
  }
  auto write_all = [&] { write_outputs(pov, code, a.output, to_stdout); };
  if (a.json) {
    using ojson = nlohmann::ordered_json;  // keys in the documented order
    ojson j = {{"target", a.target}, {"output", to_stdout ? ojson() : ojson(a.output)}};
    if (whole_scene) {  // the scene generate() renders: --scene's, else default_scene()
      const PovPlan& p = pov.plan;
      ojson files = ojson::array();
      for (const auto& f : pov.files) files.push_back(f.name);
      j["pov"] = {{"passes", p.passes}, {"native", p.native}, {"reason", p.reason}, {"routes", p.routes},
                  {"files", files}};
    }
    if (to_stdout) j["code"] = code;
    write_all();
    std::cout << j.dump() << "\n";
    return 0;
  }
  if (to_stdout) {
    std::cout << code;
    return 0;
  }
  write_all();
  return 0;
}

GenerateArgs gen;

}  // namespace

Command generate_command(CLI::App& app) {
  auto* g = app.add_subcommand("generate", "Generate GLSL, HLSL, OSL or POV-Ray code from a material file");
  g->add_option("material", gen.material,
                "The material (JSON; see 'facet schema'). May be left out for --target pov when every object of "
                "--scene has its own material");
  g->add_option("-t,--target", gen.target,
                "glsl (GLSL 3.30 core), glsl450 (Vulkan, compiles to SPIR-V), essl (OpenGL ES 3.00), "
                "osl (Cycles shader), pov (POV-Ray 3.7 scene), hlsl (Shader Model 5 pixel shader; glslangValidator -D -V "
                "compiles it to SPIR-V), wgsl (WebGPU fragment shader)")
      ->check(CLI::IsMember({"glsl", "glsl450", "essl", "osl", "pov", "hlsl", "wgsl"}))
      ->capture_default_str();
  g->add_option("--scene", gen.scene,
                "Scene for OSL's lights and POV-Ray's frame: a scene file or a built-in name (single, shadows). "
                "Default: single");
  g->add_option("--pov-route", gen.pov_route,
                "How POV-Ray draws the scene: auto (POV-Ray's own finish where every material is one exactly, "
                "else function pigments), native (the finish, or an error saying why not), exact (function "
                "pigments everywhere), fast (as auto, but meshes with an isotropic material get slope tables over "
                "n·l and n·v: no data image, approximate, the measured error printed). A mesh's lists go to "
                "FILE_meshN.inc beside -o FILE.pov, and on function pigments its corners to FILE_meshN.ppm")
      ->check(CLI::IsMember({"auto", "native", "exact", "fast"}))
      ->capture_default_str();
  g->add_flag("--library", gen.library,
              "Only the functions, for an engine (GLSL, HLSL, WGSL, OSL), or an include file declaring the texture (POV-Ray)");
  g->add_option("-o,--output", gen.output, "Output file; standard output without it. Written whole or not at all");
  g->add_flag("--json", gen.json,
              "Print one JSON object describing what was generated: target, output, and for POV-Ray scenes the "
              "passes to render (\"pov\": {passes, native, reason}); without -o the code is its \"code\"");
  g->footer(
      "Examples:\n"
      "  facet generate mat.json --target glsl450 -o mat.frag && glslangValidator -V mat.frag\n"
      "  facet generate mat.json --target hlsl -o mat.hlsl && glslangValidator -D -V -S frag -e main mat.hlsl\n"
      "  facet generate mat.json --target osl --scene shadows -o mat.osl\n"
      "  facet generate mat.json --target pov -o mat.pov      # a complete scene: sphere, camera, light\n"
      "  facet generate mat.json --target glsl --library       # just the functions: facet_reflect(n, l, v, t)\n"
      "  facet generate --target pov --scene examples/scenes/three_meshes.json -o meshes.pov  # objects' own materials\n"
      "Nothing is written when the material has an error; the exit status is then 1.");
  return {g, [] { return run_generate(gen); }};
}

}  // namespace facet::cli
