// The HLSL shading pass over the G-buffer (renderers/hlsl_shading.h) and the HLSL sweep: for every example,
// textured ones included, it compiles with glslang's HLSL front end to SPIR-V, its six
// G-buffer images at set 1, bindings 0–6, the scene's cbuffer at set 0, binding 0, the
// material's textures at set 0, bindings 1, 2, … and the lights' StructuredBuffer at set 2,
// binding 0; and the compile fails on a broken pass.
#include <filesystem>
#include <map>
#include <regex>

#include <gtest/gtest.h>

#include "catalog/material.h"
#include "catalog/program.h"
#include "core/io.h"
#include "renderers/hlsl_shading.h"
#include "renderers/process.h"
#include "targets/targets.h"
#include "targets/texture_code.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = FACET_SOURCE_DIR;

struct Compiled {
  ProcessResult run;
  std::string disassembly;
};

Compiled compile_hlsl(const std::string& source, const std::string& name) {
  const fs::path dir = test::scratch("hlsl", "compiled");  // this process's own: tests run two at a time
  fs::create_directories(dir);
  const std::string hlsl = (dir / (name + ".hlsl")).string(), spv = (dir / (name + ".spv")).string();
  write_file_atomic(hlsl, source);
  Compiled c;
  c.run = run_process({"glslangValidator", "-D", "-V", "-S", "frag", "-e", "main", hlsl, "-o", spv});
  if (c.run.exit_code == 0) c.disassembly = run_process({"spirv-dis", spv}).output;
  return c;
}

// (set, binding) of every resource the SPIR-V names: "facet_gbuffer_normal" → {1, 1}.
std::map<std::string, std::pair<int, int>> bindings(const std::string& dis) {
  std::map<std::string, int> set, binding;
  static const std::regex decoration(R"(OpDecorate %(\w+) (DescriptorSet|Binding) (\d+))");
  for (auto it = std::sregex_iterator(dis.begin(), dis.end(), decoration); it != std::sregex_iterator(); ++it)
    ((*it)[2] == "DescriptorSet" ? set : binding)[(*it)[1]] = std::stoi((*it)[3]);
  std::map<std::string, std::pair<int, int>> out;
  for (const auto& [name, s] : set) out[name] = {s, binding.count(name) ? binding[name] : -1};
  return out;
}

std::vector<fs::path> examples() {
  std::vector<fs::path> out;
  for (const char* dir : {"examples/materials", "examples/layered", "examples/textured"})
    for (const auto& e : fs::directory_iterator(kSource / dir))
      if (e.path().extension() == ".json") out.push_back(e.path());  // not examples/textured/textures/
  std::sort(out.begin(), out.end());
  return out;
}

TEST(HlslShading, EveryExampleCompilesWithTheContractsBindings) {
  int compiled = 0;
  for (const auto& path : examples()) {
    Material m = load_material(path.string());
    const std::string name = path.stem().string();
    Compiled c = compile_hlsl(hlsl_shading_source(m), name);
    ASSERT_EQ(c.run.exit_code, 0) << path << "\n" << c.run.output;
    auto b = bindings(c.disassembly);
    // The G-buffer images, at the glsl450 pass's bindings: glslang drops the uv set without
    // textures and the tangent frame without a normal map, the pass reads the others always.
    MaterialProgram p = compile(m);
    std::map<std::string, int> gbuffer = {{"facet_gbuffer_position", 0},
                                          {"facet_gbuffer_normal", 1},
                                          {"facet_gbuffer_view", 2},
                                          {"facet_gbuffer_visibility", 6}};
    if (p.has_textures()) gbuffer["facet_gbuffer_uv"] = 4;
    if (p.uses_vertex_color()) gbuffer["facet_gbuffer_color0"] = 5;
    if (p.normal_mapped()) gbuffer["facet_gbuffer_uv_tangent"] = 3;
    for (const auto& [image, binding] : gbuffer) {
      ASSERT_TRUE(b.count(image)) << name << ": " << image << " not in the SPIR-V";
      EXPECT_EQ(b[image], std::make_pair(1, binding)) << name << ": " << image;
    }
    // The StructuredBuffer's variable: glslang names its block type facet_lights, the variable facet_lights_0.
    const auto lights = b.count("facet_lights_0") ? b.find("facet_lights_0") : b.find("facet_lights");
    ASSERT_NE(lights, b.end()) << name << ": the lights' StructuredBuffer not in the SPIR-V";
    EXPECT_EQ(lights->second, std::make_pair(2, 0)) << name;
    int textures = 0;
    for (const auto& [resource, at] : b)
      if (resource.rfind("facet_texture_", 0) == 0) {
        EXPECT_EQ(at.first, 0) << name << ": " << resource;
        EXPECT_GE(at.second, 1) << name << ": " << resource;
        ++textures;
      }
    EXPECT_EQ(textures, int(image_calls(p).size())) << name;  // a value of the vertex colour alone has none
    ++compiled;
  }
  EXPECT_GE(compiled, 29);
}

// The robustness sweep's HLSL (targets.h, hlsl_sweep_source: a pixel shader evaluating the
// sweep grid) compiles for every example; the grid's functions and facet_reflect are in it.
TEST(HlslSweep, EveryExampleCompiles) {
  for (const auto& path : examples()) {
    const std::string source = hlsl_sweep_source(load_material(path.string()));
    EXPECT_NE(source.find("sweep_n_x("), std::string::npos) << path;
    Compiled c = compile_hlsl(source, path.stem().string() + "_sweep");
    EXPECT_EQ(c.run.exit_code, 0) << path << "\n" << c.run.output;
  }
}

// The compile has teeth: the pass without its visibility function, or with GLSL's vec4 in
// it, is refused.
TEST(HlslShading, BrokenPassIsRefused) {
  const std::string good = hlsl_shading_source(load_material((kSource / "examples/materials/phong.json").string()));
  ASSERT_EQ(compile_hlsl(good, "phong_good").run.exit_code, 0);
  std::string glsl = std::regex_replace(good, std::regex(R"(float4 word = )"), "vec4 word = ");
  ASSERT_NE(glsl, good);
  EXPECT_NE(compile_hlsl(glsl, "phong_vec4").run.exit_code, 0);
  const size_t at = good.find("// Light `light`'s visibility");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(compile_hlsl(good.substr(0, at), "phong_no_visibility").run.exit_code, 0);
}

}  // namespace
}  // namespace facet
