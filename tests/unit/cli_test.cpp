// The facet command line, run as a user runs it.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/io.h"
#include "renderers/process.h"
#include "renderers/renderer.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kFacet = FACET_BIN;
const fs::path kSource = FACET_SOURCE_DIR;

fs::path scratch(const std::string& name) { return test::scratch("cli", name); }
using test::facet;

std::vector<std::string> malformed_files() {
  json expected = json::parse(read_file((kSource / "tests/malformed/EXPECTED").string()));
  std::vector<std::string> names;
  for (const auto& [name, path] : expected.items()) names.push_back(name);
  return names;
}

class Malformed : public ::testing::TestWithParam<std::string> {};

// Each malformed file: non-zero exit, a message naming the file and the key
// path, and no output file — for every target.
TEST_P(Malformed, FailsNamingTheKeyPathAndWritesNothing) {
  json expected = json::parse(read_file((kSource / "tests/malformed/EXPECTED").string()));
  const std::string file = (kSource / "tests/malformed" / GetParam()).string();
  const std::string path = expected[GetParam()];
  for (const char* target : {"glsl", "osl", "pov"}) {
    fs::path out = scratch(GetParam() + "." + target);
    fs::remove(out);
    ProcessResult r = facet({"generate", file, "--target", target, "-o", out.string()});
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(file), std::string::npos) << "the message names the file: " << r.output;
    EXPECT_NE(r.output.find(": " + path + ": "), std::string::npos) << "the message names " << path << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing is written";
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, Malformed, ::testing::ValuesIn(malformed_files()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

TEST(Cli, MalformedCorpusHasAtLeastTwentyFiles) { EXPECT_GE(malformed_files().size(), 20u); }

// Numbers float32 targets cannot hold (docs/float32.md): the issue's material, a
// scene with a light of colour 1e39, a glTF whose emission strength is 1e39. Every
// command that reads them refuses, naming the file, the key path and the allowed
// range, exit 1, nothing written.
TEST(Cli, Float32LimitsRefusedByEveryCommand) {
  const std::string material = (kSource / "tests/malformed/float32_issue.json").string();
  const fs::path scene = scratch("float32_scene.json");
  write_file_atomic(scene.string(), R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [2, 2, 2], "color": [1e39, 1, 1]}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})");
  json g = json::parse(read_file((kSource / "tests/gltf/one_triangle.gltf").string()));
  g["materials"][0]["emissiveFactor"] = {1, 1, 1};
  g["materials"][0]["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 1e39}}}};
  g["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  const fs::path gltf = scratch("float32.gltf");
  write_file_atomic(gltf.string(), g.dump());
  struct Case {
    std::vector<std::string> args;  // the output is the last argument
    std::string file, path, allowed;
  };
  const std::string out = scratch("float32_out").string();
  const std::string color = "or one number for grey, each in [0, 10000]";
  const std::string light = "or one number for grey, each in [0, 1000000]";  // kLightColorMax: real light powers
  const std::vector<Case> cases = {
      {{"generate", material, "--target", "glsl", "-o", out + ".frag"}, material, "diffuse.color[0]", color},
      {{"generate", material, "--target", "osl", "-o", out + ".osl"}, material, "specular.n",
       "allowed: a number in [1, 1000000]"},
      {{"validate", material, "--renderers", "reference", "--out", out + "_validate"}, material, "diffuse.color[0]", color},
      {{"sweep", material, "--renderers", "reference", "--workdir", out + "_sweep"}, material, "specular.n", "[1, 1000000]"},
      {{"render", material, "-r", "reference", "-o", out + ".pfm"}, material, "diffuse.color[0]", color},
      {{"render", (kSource / "examples/materials/lambert.json").string(), "-r", "reference", "--scene", scene.string(),
        "-o", out + "_scene.pfm"},
       scene.string(), "lights[0].color[0]", light},
      {{"export-gltf", scene.string(), "-o", out + ".gltf"}, scene.string(), "lights[0].color[0]", light},
      {{"export-gltf", "single", "--material", material, "-o", out + "_m.gltf"}, material, "diffuse.color[0]", color},
      {{"import-gltf", gltf.string(), "-o", out + "_imported.json"}, gltf.string(), "materials[0] (as a facet material: emission[0])",
       color},
  };
  for (const auto& c : cases) {
    const std::string written = c.args.back();
    fs::remove_all(written);
    ProcessResult r = facet(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args[0] << ": " << r.output;
    EXPECT_NE(r.output.find(c.file), std::string::npos) << c.args[0] << " names the file: " << r.output;
    EXPECT_NE(r.output.find(c.path), std::string::npos) << c.args[0] << " names " << c.path << ": " << r.output;
    EXPECT_NE(r.output.find(c.allowed), std::string::npos) << c.args[0] << " says " << c.allowed << ": " << r.output;
    EXPECT_FALSE(fs::exists(written)) << c.args[0] << " writes nothing";
  }
}

TEST(Cli, AFailedGenerateLeavesThePreviousOutputIntact) {
  fs::path out = scratch("previous.frag");
  write_file_atomic(out.string(), "previous contents\n");
  ProcessResult r = facet({"generate", (kSource / "tests/malformed/unknown_model.json").string(), "-o", out.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(read_file(out.string()), "previous contents\n");
}

// Interrupted while writing: the shell's file-size limit (ulimit -f) stops
// facet in the middle of writing a 7 MB POV-Ray scene, by SIGXFSZ (killed) or,
// with the signal ignored, by a failing write(2). Either way the previous file
// is untouched; on the error path the temporary file is gone too.
std::vector<std::string> hidden_temporaries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".facet-") != std::string::npos) out.push_back(e.path().string());
  return out;
}

ProcessResult limited_generate(const fs::path& out, bool ignore_signal) {
  std::string cmd = std::string(ignore_signal ? "trap '' XFSZ; " : "") + "ulimit -f 512; exec '" + kFacet +
                    "' generate --target pov --scene '" + (kSource / "examples/scenes/three_meshes.json").string() +
                    "' -o '" + out.string() + "'";
  return run_process({"sh", "-c", cmd});
}

// A folder of its own holding scene.pov from an earlier run.
fs::path previous_output(const std::string& folder) {
  fs::path dir = scratch(folder);
  fs::create_directories(dir);
  write_file_atomic((dir / "scene.pov").string(), "previous contents\n");
  return dir / "scene.pov";
}

TEST(Cli, AKilledWriteLeavesThePreviousOutputIntact) {
  fs::path out = previous_output("killed"), dir = out.parent_path();
  ProcessResult r = limited_generate(out, false);
  EXPECT_NE(r.exit_code, 0) << "the file-size limit should have stopped facet: " << r.output;
  EXPECT_EQ(read_file(out.string()), "previous contents\n");
  // The partial data went to a hidden temporary file, which a killed process cannot remove.
  std::vector<std::string> temps = hidden_temporaries(dir);
  ASSERT_EQ(temps.size(), 1u);
  EXPECT_GT(fs::file_size(temps[0]), 0u);
}

TEST(Cli, AFailedWriteLeavesThePreviousOutputIntactAndNoTemporary) {
  fs::path out = previous_output("efbig"), dir = out.parent_path();
  ProcessResult r = limited_generate(out, true);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  // The first file too big for the limit is a mesh's include file, written before the scene.
  EXPECT_NE(r.output.find((dir / "scene_mesh0.inc").string() + ": cannot write"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(out.string()), "previous contents\n");
  EXPECT_TRUE(hidden_temporaries(dir).empty());
  EXPECT_FALSE(fs::exists(dir / "scene_mesh0.inc"));
}

// A textured material generates GLSL and OSL that sample its images, and a POV-Ray scene
// with its images beside it; a scene whose mesh lacks the coordinate set a textured
// parameter reads is refused, naming the file, the object and the key, exit 1, nothing written.
TEST(Cli, TexturedMaterialsGenerateForEveryTarget) {
  const std::string material = (kSource / "examples/textured/textured_ggx.json").string();
  fs::path frag = scratch("textured.frag");
  ProcessResult ok = facet({"generate", material, "--target", "glsl", "-o", frag.string()});
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  std::string code = read_file(frag.string());
  EXPECT_NE(code.find("uniform sampler2D facet_texture_specular_alpha;"), std::string::npos);
  EXPECT_NE(code.find("facet_sample_textures(facet_texcoord0, facet_texcoord1);"), std::string::npos);
  ProcessResult osl = facet({"generate", material, "--target", "osl", "-o", scratch("textured.osl").string()});
  ASSERT_EQ(osl.exit_code, 0) << osl.output;
  EXPECT_NE(read_file(scratch("textured.osl").string()).find("string facet_texture_specular_alpha = \""),
            std::string::npos);
  const fs::path dir = scratch("textured_pov");
  fs::create_directories(dir);
  ProcessResult pov = facet({"generate", material, "--target", "pov", "-o", (dir / "t.pov").string()});
  ASSERT_EQ(pov.exit_code, 0) << pov.output;
  EXPECT_TRUE(fs::exists(dir / "t_texture0.ppm"));
  EXPECT_TRUE(fs::exists(dir / "t_texture1.ppm"));
  // A mesh without the texture coordinate set a textured parameter reads: refused.
  const fs::path scene = scratch("textured_mesh.json");
  write_file_atomic(scene.string(), R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
    "lights": [{"type": "point", "position": [2, 2, 2]}],
    "objects": [{"type": "mesh", "name": "tri", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                 "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1]], "triangles": [[0, 1, 2]]}]})");
  for (const char* target : {"pov", "glsl"}) {
    const fs::path out = scratch(std::string("textured_mesh.") + target);
    ProcessResult r = facet({"generate", material, "--scene", scene.string(), "--target", target, "-o", out.string()});
    EXPECT_EQ(r.exit_code, 1) << target;
    EXPECT_NE(r.output.find("textured_mesh.json: objects[0]"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("mesh \"tri\" has no texture coordinates set 0"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("specular.alpha"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << target;
  }
}

TEST(Cli, GenerateWritesTheFile) {
  fs::path out = scratch("lambert.frag");
  fs::remove(out);
  ProcessResult r = facet({"generate", (kSource / "examples/materials/lambert.json").string(), "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string code = read_file(out.string());
  EXPECT_EQ(code.rfind("#version 330 core", 0), 0u);
  EXPECT_NE(code.find("rho_lambert"), std::string::npos);
}

// --json describes what was generated; tools (the Blender add-on) read POV-Ray's pass count from it.
// --pov-route: native refuses what POV-Ray's finish cannot draw, naming the object, and
// writes nothing; fast draws the isotropic meshes through slope tables (no data image)
// and says so, with its measured error; every object's route is on stderr.
TEST(Cli, PovRoutesAreChosenAndSaid) {
  const std::string scene = (kSource / "examples/scenes/three_meshes.json").string();
  fs::path out = scratch("routes.pov");
  fs::remove(out);
  ProcessResult r = facet({"generate", "--target", "pov", "--scene", scene, "--pov-route", "native", "-o", out.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("three_meshes.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--pov-route native: object \"sphere\": ggx is not a POV-Ray finish"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(scratch("routes_mesh0.ppm")));
  // Lobes that are finishes (Lambert, Phong) under a layer are not: a finish adds its terms, a
  // layer weights what lies under it.
  r = facet({"generate", (kSource / "examples/layered/velvet_phong.json").string(), "--target", "pov", "--pov-route",
             "native", "-o", out.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("layers[0] (sheen) weights the lobes under it, which POV-Ray's finish only adds"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));

  r = facet({"generate", "--target", "pov", "--scene", scene, "--pov-route", "fast", "--json", "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json j = json::parse(r.output);
  const auto& routes = j["pov"]["routes"];
  ASSERT_EQ(routes.size(), 4u);
  EXPECT_NE(routes[0].get<std::string>().find("slope tables"), std::string::npos) << routes[0];  // GGX: isotropic
  EXPECT_NE(routes[0].get<std::string>().find("measured"), std::string::npos) << routes[0];
  EXPECT_NE(routes[2].get<std::string>().find("data image"), std::string::npos) << routes[2];  // Ward reads t
  EXPECT_EQ(j["pov"]["files"], json::array({"routes_mesh0.inc", "routes_mesh1.inc", "routes_mesh2.inc",
                                            "routes_mesh2.ppm", "routes_mesh3.inc"}))
      << "each mesh's lists, and a data image for the Ward torus only";
  EXPECT_NE(read_file(out.string()).find("slope { point_at"), std::string::npos);

  r = facet({"generate", "--target", "pov", "--scene", scene, "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("facet: object \"torus\" (mesh of"), std::string::npos) << "routes on stderr: " << r.output;
  r = facet({"generate", "--target", "pov", "--scene", scene});
  EXPECT_EQ(r.exit_code, 1) << "the data images need a folder: -o";
  EXPECT_NE(r.output.find("give -o FILE.pov"), std::string::npos) << r.output;
}

TEST(Cli, GenerateJsonDescribesTheOutput) {
  fs::path out = scratch("three_meshes.pov");
  fs::remove(out);
  ProcessResult r = facet({"generate", "--target", "pov", "--scene",
                           (kSource / "examples/scenes/three_meshes.json").string(), "-o", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json j = json::parse(r.output);
  EXPECT_EQ(j["target"], "pov");
  EXPECT_EQ(j["output"], out.string());
  EXPECT_FALSE(j.contains("code"));
  EXPECT_EQ(j["pov"]["native"], false);  // Oren–Nayar, GGX, Ward: function pigments, a pass per light
  EXPECT_FALSE(j["pov"]["reason"].get<std::string>().empty());
  ASSERT_EQ(j["pov"]["routes"].size(), 4u) << "one line per object";
  EXPECT_NE(j["pov"]["routes"][0].get<std::string>().find("data image"), std::string::npos) << j["pov"]["routes"][0];
  ASSERT_EQ(j["pov"]["files"].size(), 8u) << "each mesh's lists and its data image";
  for (const auto& f : j["pov"]["files"]) EXPECT_TRUE(fs::exists(out.parent_path() / f.get<std::string>())) << f;
  std::string pov = read_file(out.string());
  std::string declared = "#declare Facet_Passes = " + std::to_string(j["pov"]["passes"].get<int>()) + ";";
  EXPECT_NE(pov.find(declared), std::string::npos) << "the JSON and the scene agree on " << declared;

  const std::string lambert = (kSource / "examples/materials/lambert.json").string();
  ProcessResult plain = facet({"generate", lambert});
  r = facet({"generate", lambert, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  j = json::parse(r.output);
  EXPECT_EQ(j["target"], "glsl");
  EXPECT_TRUE(j["output"].is_null());
  EXPECT_EQ(j["code"], plain.output) << "without -o the code is in the JSON";
  EXPECT_FALSE(j.contains("pov"));
  r = facet({"generate", lambert, "--target", "pov", "--json"});
  j = json::parse(r.output);
  EXPECT_EQ(j["pov"]["passes"], 1);
  EXPECT_EQ(j["pov"]["native"], true) << "Lambert is POV-Ray's own finish";
  EXPECT_EQ(j["pov"]["reason"], "");
  EXPECT_EQ(j["pov"]["files"], json::array()) << "a sphere reads no file";
  r = facet({"generate", lambert, "--target", "pov", "--library", "--json"});
  EXPECT_FALSE(json::parse(r.output).contains("pov")) << "an include file has no passes";
}

TEST(Cli, EvalLambertIsKdCosine) {
  fs::path in = scratch("eval_in.json");
  // n·l = cos 60°, so Lambert gives k_d / 2; the second set is below the horizon.
  write_file_atomic(in.string(), R"([{"n": [0, 0, 2], "l": [0, 0.8660254037844386, 0.5], "v": [0, 0, 1]},
                                     {"n": [0, 0, 1], "l": [0, 0, -1], "v": [0, 0, 1]}])");
  ProcessResult r = facet({"eval", (kSource / "examples/materials/lambert.json").string()}, in.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json out = json::parse(r.output);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(out[0][0].get<double>(), 0.8 * 0.5, 1e-15);
  EXPECT_NEAR(out[0][1].get<double>(), 0.5 * 0.5, 1e-15);
  EXPECT_NEAR(out[0][2].get<double>(), 0.3 * 0.5, 1e-15);
  EXPECT_EQ(out[1][0].get<double>(), 0.0);
}

TEST(Cli, EvalUsesTheGivenTangent) {
  fs::path in = scratch("eval_tangent.json");
  // Heidrich–Seidel reads l·t and v·t: two tangents, two answers.
  write_file_atomic(in.string(), R"([{"n": [0, 0, 1], "l": [1, 0, 1], "v": [-1, 0.2, 1], "t": [1, 0, 0]},
                                     {"n": [0, 0, 1], "l": [1, 0, 1], "v": [-1, 0.2, 1], "t": [0, 1, 0]}])");
  ProcessResult r = facet({"eval", (kSource / "examples/materials/heidrich_seidel.json").string()}, in.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json out = json::parse(r.output);
  EXPECT_NE(out[0][0].get<double>(), out[1][0].get<double>());
}

TEST(Cli, EvalRejectsBadDirectionSets) {
  fs::path in = scratch("eval_bad.json");
  write_file_atomic(in.string(), R"([{"n": [0, 0, 0], "l": [0, 0, 1], "v": [0, 0, 1]}, {"n": [0, 0, 1], "l": [0, 1]}])");
  ProcessResult r = facet({"eval", (kSource / "examples/materials/lambert.json").string()}, in.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("[0].n"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("[1].l"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("[1].v"), std::string::npos) << r.output;
}

TEST(Cli, ModelsJsonListsEveryLobe) {
  ProcessResult r = facet({"models", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json cat = json::parse(r.output);
  std::vector<std::string> names;
  for (const auto& m : cat["sections"]["diffuse"]) names.push_back(m["name"]);
  for (const auto& m : cat["sections"]["specular"]) names.push_back(m["name"]);
  for (const char* want : {"lambert", "minnaert", "minnaert_velvet", "oren_nayar", "phong", "blinn_phong", "gaussian",
                           "heidrich_seidel", "beckmann", "cook_torrance", "ggx", "blinn", "ward", "ward_nvidia"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
}

TEST(Cli, HelpTeachesWithExamples) {
  for (const char* cmd : {"generate", "eval", "models", "render"}) {
    ProcessResult r = facet({cmd, "--help"});
    EXPECT_EQ(r.exit_code, 0) << cmd;
    if (std::string(cmd) != "models") {
      EXPECT_NE(r.output.find("xample"), std::string::npos) << cmd << r.output;
    }
  }
}

// `facet render` with every renderer of the registry: an image, and for all but
// the reference its comparison with the reference, within the check's tolerance.
TEST(Cli, RenderWithEveryRenderer) {
  for (const auto& name : renderer_names()) {
    fs::path out = scratch("render_" + name + ".pfm");
    fs::remove(out);
    ProcessResult r = facet({"render", (kSource / "examples/materials/ggx.json").string(), "-r", name, "--size", "48x40",
                             "--check", "2e-3", "--workdir", scratch("render_" + name).string(), "-o", out.string()});
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.output;
    EXPECT_TRUE(fs::exists(out)) << name;
    if (find_renderer(name)->reference) continue;
    EXPECT_NE(r.output.find(name + " vs reference, ggx_plastic: "), std::string::npos) << name << ": " << r.output;
    EXPECT_NE(r.output.find(" 0 of "), std::string::npos) << name << ": " << r.output;
  }
  ProcessResult r = facet({"render", (kSource / "examples/materials/ggx.json").string(), "-r", "nosuch"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("nosuch"), std::string::npos) << r.output;
}

// A renderer that cannot run says why, and `facet render` fails.
TEST(Cli, RenderWithARendererThatCannotRunSaysWhy) {
  ProcessResult r = run_process({kFacet, "render", (kSource / "examples/materials/ggx.json").string(), "-r", "osl",
                                 "--size", "16x16", "--workdir", scratch("render_no_python").string()},
                                "", {"FACET_PYTHON=/nonexistent/python3"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("error: Cycles: cannot run /nonexistent/python3"), std::string::npos) << r.output;
}

// The build's Python path that this user cannot look at (a folder without permission, or, as
// here whoever runs the test, a link loop or a name too long: stat fails with something other
// than "not found") is passed over for "python3", never thrown out of `facet render -r
// reference` (issue 28). FACET_PYTHON still wins.
TEST(Cli, ABuildPythonThatCannotBeLookedAtFallsBackToPython3) {
  fs::path dir = scratch("python_loop");
  fs::create_directories(dir);
  fs::remove(dir / "loop");
  fs::create_symlink("loop", dir / "loop");
  const std::string looped = (dir / "loop" / "bin" / "python").string();
  std::error_code ec;
  EXPECT_FALSE(fs::exists(looped, ec));
  ASSERT_TRUE(ec) << "stat of a path through a link loop should fail with ELOOP";
  EXPECT_THROW((void)fs::exists(looped), fs::filesystem_error) << "the throwing form is what crashed before";
  EXPECT_EQ(choose_python(nullptr, looped.c_str()), "python3");
  const std::string too_long = "/" + std::string(5000, 'p') + "/python";
  EXPECT_EQ(choose_python("", too_long.c_str()), "python3");
  EXPECT_EQ(choose_python("/opt/bpy/python", looped.c_str()), "/opt/bpy/python");
  const std::string present = kFacet;  // any file that is there
  EXPECT_EQ(choose_python(nullptr, present.c_str()), present);
  EXPECT_EQ(choose_python(nullptr, nullptr), "python3");
}

TEST(Cli, UnknownTargetIsAUsageError) {
  ProcessResult r = facet({"generate", (kSource / "examples/materials/lambert.json").string(), "--target", "metal"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("metal"), std::string::npos) << r.output;
}

// facet cost's frame shades a sphere without texture coordinates: a material that reads images
// is refused before anything runs, naming the file and each textured key (it once ended in an
// uncaught exception from the POV-Ray column).
TEST(Cli, CostRefusesAMaterialThatReadsImages) {
  ProcessResult r = facet({"cost", (kSource / "examples/textured/textured_specular_sheen.json").string(),
                           "--no-timings", "--no-callgrind"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  for (const char* key : {"specular.specular_color", "specular.sheen_color", "specular.sheen_roughness"})
    EXPECT_NE(r.output.find(std::string("textured_specular_sheen.json: ") + key + ": an image texture"),
              std::string::npos)
        << r.output;
  EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
}

// Every renderer reading the same wrong scene agrees with it perfectly: validate says which
// scenes show no shading instead of passing them. A cube whose normals point into it (as a
// transform that turned them the wrong way made them), a wall no light reaches, and a scene
// without lights are each reported as uninformative, naming the object; the same cube with
// its normals outwards passes.
TEST(Cli, ValidateReportsScenesThatShowNoShading) {
  const json camera = {{"position", {2, 1.5, 3}}, {"look_at", {0, 0, 0}}, {"fov", 40}};
  json cube = {{"type", "mesh"}, {"name", "cube"}, {"positions", json::array()}, {"normals", json::array()},
               {"triangles", json::array()}};
  const int faces[6][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                              {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                              {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  for (const auto& f : faces) {
    const size_t base = cube["positions"].size();
    for (const auto& c : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      json p = json::array();
      for (int k = 0; k < 3; ++k) p.push_back(0.5 * (f[0][k] + c.first * f[1][k] + c.second * f[2][k]));
      cube["positions"].push_back(p);
      cube["normals"].push_back({f[0][0], f[0][1], f[0][2]});
    }
    cube["triangles"].push_back({base, base + 1, base + 2});
    cube["triangles"].push_back({base, base + 2, base + 3});
  }
  json inside_out = cube;
  for (auto& n : inside_out["normals"]) n = {-n[0].get<int>(), -n[1].get<int>(), -n[2].get<int>()};
  const json light = {{"type", "point"}, {"position", {3, 4, 5}}, {"color", 30}, {"attenuation", "inverse_square"}};
  // A narrow spot on the ball: the wall behind it lies outside the cone or in the ball's shadow.
  const json spot = {{"type", "spot"},   {"position", {2, 3, 4}}, {"direction", {-2, -3, -4}},
                     {"cutoff", 10},     {"color", 30},          {"attenuation", "inverse_square"}};
  const json sphere = {{"type", "sphere"}, {"name", "ball"}, {"center", {0, 0, 0}}, {"radius", 1}};
  const json wall = {{"type", "plane"}, {"name", "wall"}, {"point", {0, 0, -2.5}}, {"normal", {0, 0, 1}}, {"size", 1.5}};
  struct Case {
    std::string name;
    json scene;
    int exit_code;
    std::string says;
  };
  const std::vector<Case> cases = {
      {"outwards", {{"camera", camera}, {"objects", {cube}}, {"lights", {light}}}, 0, "1 of 1 comparisons pass"},
      {"inside_out", {{"camera", camera}, {"objects", {inside_out}}, {"lights", {light}}}, 1,
       "objects show no shading: \"cube\" faces away from the camera at 100 %"},
      {"wall_unlit", {{"camera", camera}, {"objects", {sphere, wall}}, {"lights", {spot}}}, 1,
       "objects show no shading: \"wall\" no light reaches any of its"},
      {"no_lights", {{"camera", camera}, {"objects", {sphere}}, {"lights", json::array()}}, 1,
       "the reference is black at all 952 pixels where objects are visible; objects show no shading: \"ball\" no "
       "light reaches"},
  };
  for (const auto& c : cases) {
    json scene = c.scene;
    scene["name"] = c.name;
    const fs::path file = scratch(c.name + ".json");
    write_file_atomic(file.string(), scene.dump());
    ProcessResult r = facet({"validate", (kSource / "examples/materials/lambert.json").string(), "--scene",
                             file.string(), "--renderers", "reference,glsl", "--size", "64x48", "--out",
                             scratch(c.name + "_out").string()});
    EXPECT_EQ(r.exit_code, c.exit_code) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.name << ": " << r.output;
    if (c.exit_code) {
      EXPECT_NE(r.output.find("1 uninformative"), std::string::npos) << c.name << ": " << r.output;
    }
  }
}

TEST(Cli, PublishedSchemaIsTheGeneratedOne) {
  ProcessResult r = facet({"schema"});
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(json::parse(r.output), json::parse(read_file((kSource / "schemas/material.schema.json").string())))
      << "run: build/bin/facet schema > schemas/material.schema.json";
  r = facet({"schema", "--scene"});
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(json::parse(r.output), json::parse(read_file((kSource / "schemas/scene.schema.json").string())))
      << "run: build/bin/facet schema --scene > schemas/scene.schema.json";
}


// A vector so short that normalizing it underflows (issue 28: a directional light [0, -1e-300, 0]
// gave 3,660 NaN pixels, a camera up [0, 1e-300, 0] a black image, a tangent axis [1e-300, 0, 0]
// `inf` in every target's code) is refused like the zero vector, naming the key.
TEST(Cli, DirectionsTooShortToNormalizeAreRefused) {
  const json lambert = {{"model", "lambert"}, {"color", {0.5, 0.5, 0.5}}};
  const json material = {{"name", "tiny"},
                         {"diffuse", lambert},
                         {"specular", {{"model", "ward"}, {"color", {1, 1, 1}}, {"alpha_x", 0.2}, {"alpha_y", 0.4}}},
                         {"tangent_axis", {1e-300, 0, 0}}};
  const fs::path mfile = scratch("tiny_tangent.json");
  write_file_atomic(mfile.string(), material.dump());
  ProcessResult r = facet({"generate", mfile.string(), "--target", "glsl"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("tangent_axis: [1e-300, 0, 0] is too short to be a direction"), std::string::npos)
      << r.output;
  const json scene = {
      {"camera", {{"position", {0, 0, 4}}, {"look_at", {0, 0, 0}}, {"up", {0, 1e-300, 0}}, {"fov", 40}}},
      {"materials", {{"grey", {{"diffuse", lambert}}}}},
      {"objects",
       {{{"type", "mesh"}, {"name", "tri"}, {"material", "grey"}, {"positions", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
         {"normals", {{0, 0, 1}, {0, 0, 1e-300}, {0, 0, 1}}}, {"triangles", {{0, 1, 2}}}}}},
      {"lights", {{{"type", "directional"}, {"direction", {0, -1e-300, 0}}, {"color", {1, 1, 1}}}}}};
  const fs::path sfile = scratch("tiny_scene.json");
  write_file_atomic(sfile.string(), scene.dump());
  r = facet({"render", "--scene", sfile.string(), "--size", "8x8", "-o", scratch("tiny.pfm").string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  for (const char* key : {"camera.up: [0, 1e-300, 0]", "objects[0].normals[1]: [0, 0, 1e-300]",
                          "lights[0].direction: [0, -1e-300, 0]"})
    EXPECT_NE(r.output.find(std::string(key) + " is too short to be a direction"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(scratch("tiny.pfm")));
}

}  // namespace
}  // namespace facet
