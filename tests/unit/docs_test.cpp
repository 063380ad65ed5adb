// `facet plot` and `facet docs` run as a user runs them, and the cost rows the
// docs read: pages with every image present, failed renderers shown failed,
// bad inputs named and nothing written.
//
// tests/fixtures/cost_rows*.fixture.json are hand-written fixtures in the
// format `facet cost --json` prints, not measurements.
#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analysis/cost.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "docs/docs.h"
#include "renderers/renderer.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::facet;

const fs::path kSource = FACET_SOURCE_DIR;
const std::string kFixture = (kSource / "tests/fixtures/cost_rows.fixture.json").string();
const std::string kBadFixture = (kSource / "tests/fixtures/cost_rows_bad.fixture.json").string();

fs::path scratch(const std::string& name) { return test::scratch("docs", name); }

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Every src= and href= of a page, as written.
std::vector<std::string> links(const std::string& html) {
  std::vector<std::string> out;
  std::regex link(R"re((?:src|href)="([^"]*)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1]);
  return out;
}

// Every page links only files that exist, none on the network, and runs no script.
void expect_self_contained(const fs::path& dir) {
  size_t pages = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".html" || e.path().parent_path().filename() == "validate") continue;
    ++pages;
    std::string html = read_file(e.path().string());
    EXPECT_EQ(html.find("<script"), std::string::npos) << e.path();
    for (const auto& l : links(html)) {
      EXPECT_EQ(l.find("://"), std::string::npos) << e.path() << " links the network: " << l;
      fs::path target = e.path().parent_path() / l.substr(0, l.find('#'));
      EXPECT_TRUE(fs::exists(target)) << e.path() << " links " << l << ", which is missing";
    }
  }
  EXPECT_GE(pages, 3u);
}

// ---------------------------------------------------------------- cost rows

TEST(CostRows, TheAgreedFormatReadsBack) {
  CostTable t = load_cost_rows(kFixture);
  EXPECT_EQ(t.baseline, "lambert");
  ASSERT_EQ(t.rows.size(), 2u);
  const CostRow* lambert = t.find("lambert");
  ASSERT_TRUE(lambert);
  EXPECT_EQ(lambert->diffuse, "lambert");
  EXPECT_EQ(lambert->specular, "");
  const json& glsl = lambert->cell("glsl").figures;
  ASSERT_TRUE(glsl.contains("spirv"));
  EXPECT_EQ(glsl["spirv"], 33);
  EXPECT_EQ(lambert->cell("glsl").number("callgrind_per_pixel"), 43.6);
  EXPECT_TRUE(lambert->cell("pov").flag("native"));
  EXPECT_TRUE(lambert->cell("pov").figures["functions"].is_null());
  const CostRow* phong = t.find("phong");
  ASSERT_TRUE(phong);
  EXPECT_EQ(phong->cell("osl").error, "FIXTURE: the OSL timing run did not finish");
  EXPECT_TRUE(phong->cell("osl").figures.empty());
  ASSERT_TRUE(phong->cell("glsl").figures.contains("fixture_extra")) << "a figure the format does not name is kept";
  EXPECT_EQ(phong->cell("glsl").figures["fixture_extra"], 7);
  EXPECT_EQ(t.find("ggx"), nullptr);
}

// What `facet cost --json` prints (costs_json) is what the docs read, whole:
// the rows, the frame and the tools; and the docs take a measurement's rows as
// they are (cost_table), the same as read back.
TEST(CostRows, WhatFacetCostPrintsReadsBack) {
  CostRow lambert;
  lambert.name = lambert.material = lambert.diffuse = "lambert";
  lambert.cell("glsl").figures = {{"spirv", 65}, {"callgrind_per_pixel", 122.25}, {"callgrind_relative", 1.0}};
  lambert.cell("osl").figures = {{"instructions", 47}, {"ns_per_pixel", nullptr}, {"relative", nullptr}};
  lambert.cell("pov").figures = {{"native", true}, {"functions", nullptr}, {"ns_per_pixel", nullptr}, {"relative", nullptr}};
  CostRow ggx;
  ggx.name = ggx.material = ggx.specular = "ggx";
  ggx.cell("glsl").figures = {{"spirv", 99}, {"callgrind_per_pixel", nullptr}, {"callgrind_relative", nullptr}};
  ggx.cell("osl").error = "Blender did not start";
  ggx.cell("osl").figures = {{"instructions", 0}};
  ggx.cell("pov").figures = {{"native", false}, {"functions", 25}, {"ns_per_pixel", nullptr}, {"relative", nullptr}};
  CostBaselines b;
  b.spirv_empty = 61;
  b.valgrind = "valgrind-3.19.0";
  CostTable t = parse_cost_rows(costs_json({lambert, ggx}, b), "facet cost");
  EXPECT_EQ(t.baseline, "lambert");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.find("lambert")->cell("glsl").figures["spirv"], 65);
  EXPECT_EQ(t.find("ggx")->cell("osl").error, "Blender did not start");
  EXPECT_EQ(t.find("ggx")->cell("pov").figures["functions"], 25);
  EXPECT_EQ(t.frame["glsl_spirv"], 61);
  EXPECT_EQ(t.tools["valgrind"], "valgrind-3.19.0");
  CostTable measured = cost_table({lambert, ggx}, b, "facet cost");
  ASSERT_EQ(measured.rows.size(), t.rows.size());
  for (size_t i = 0; i < t.rows.size(); ++i)
    for (const auto& format : cost_format()) {
      EXPECT_EQ(measured.rows[i].cell(format.target).error, t.rows[i].cell(format.target).error);
      EXPECT_EQ(measured.rows[i].cell(format.target).figures, t.rows[i].cell(format.target).figures);
    }
  EXPECT_EQ(measured.frame, t.frame);
  EXPECT_EQ(measured.tools, t.tools);
  EXPECT_EQ(measured.baseline, t.baseline);
}

// Each problem names the file and its key path.
void expect_rejected(const std::string& text, const std::vector<std::string>& paths) {
  try {
    parse_cost_rows(json::parse(text), "cost.json");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const InputError& e) {
    std::string all;
    for (const auto& d : e.diagnostics()) {
      EXPECT_EQ(d.file, "cost.json");
      all += d.format() + "\n";
    }
    for (const auto& p : paths) EXPECT_NE(all.find("cost.json: " + p + ": "), std::string::npos) << p << " in:\n" << all;
  }
}

TEST(CostRows, ProblemsNameTheFileAndTheKeyPath) {
  const std::string good = R"("glsl": {"spirv": 1, "callgrind_per_pixel": 2, "callgrind_relative": 1},
                              "osl": {"error": "x"}, "pov": {"error": "y"})";
  expect_rejected("[]", {"(document)"});
  expect_rejected(R"({"baseline": "lambert"})", {"rows"});
  expect_rejected(R"({"baseline": "lambert", "rows": [3]})", {"rows[0]"});
  expect_rejected(R"({"baseline": "lambert", "rows": [{"nmae": "a", "material": "m", "diffuse": null, "specular": null, )" +
                      good + "}]}",
                  {"rows[0].nmae", "rows[0].name"});
  expect_rejected(R"({"baseline": "lambert", "rows": [{"name": "a", "material": "m", "diffuse": null, "specular": null,
                      "glsl": {"spirv": -1, "callgrind_per_pixel": 2, "callgrind_relative": 1},
                      "osl": {"instructions": 1.5, "ns_per_pixel": 1, "relative": 1}, "pov": {"error": ""}}]})",
                  {"rows[0].glsl.spirv", "rows[0].osl.instructions", "rows[0].pov.error"});
  expect_rejected(R"({"baseline": "lambert", "rows": [{"name": "a", "material": "m", "diffuse": 1, "specular": null, )" +
                      good + R"(}, {"name": "a", "material": "m", "diffuse": null, "specular": null, )" + good + "}]}",
                  {"rows[0].diffuse", "rows[1].name"});
  try {
    load_cost_rows(kBadFixture);
    ADD_FAILURE() << "the bad fixture was accepted";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].file, kBadFixture);
    EXPECT_EQ(e.diagnostics()[0].path, "rows[0].glsl.spirv");
  }
}

// ---------------------------------------------------------------- facet plot

TEST(PlotCli, WritesSvgAndPng) {
  for (const char* ext : {".svg", ".png"}) {
    fs::path out = scratch(std::string("ward") + ext);
    fs::remove(out);
    ProcessResult r = facet({"plot", (kSource / "examples/materials/ward.json").string(), "--light-angle", "30", "-o", out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_GT(fs::file_size(out), 1000u);
  }
  fs::path out = scratch("ward3d.png");
  ProcessResult r = facet({"plot", (kSource / "examples/materials/ward.json").string(), "--view", "lobe3d", "--scale", "log",
                           "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_file(out.string()).substr(1, 3), "PNG");
}

TEST(PlotCli, BadInputsNameTheFileOrOptionAndWriteNothing) {
  const std::string good = (kSource / "examples/materials/phong.json").string();
  const std::string bad = (kSource / "tests/malformed/unknown_model.json").string();
  struct Case {
    std::vector<std::string> args;
    std::string out, named;
  };
  std::vector<Case> cases = {
      {{"plot", bad}, "bad.svg", bad + ": diffuse.model: "},
      {{"plot", (kSource / "no/such.json").string()}, "missing.svg", "no/such.json"},
      {{"plot", good, "--light-angle", "90"}, "angle.svg", "--light-angle: 90 is out of range"},
      {{"plot", good, "--light-angle", "-5"}, "negative.svg", "--light-angle: -5 is out of range"},
      {{"plot", good}, "plot.txt", "-o: "},
      {{"plot", good, "--view", "lobe3d"}, "lobe.svg", "-o: "},
  };
  for (auto c : cases) {
    fs::path out = scratch(c.out);
    fs::remove(out);
    c.args.push_back("-o");
    c.args.push_back(out.string());
    ProcessResult r = facet(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.out << ": " << r.output;
    EXPECT_NE(r.output.find(c.named), std::string::npos) << "expected \"" << c.named << "\" in: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.out;
  }
  // A failed run leaves the previous diagram as it was.
  fs::path previous = scratch("previous.svg");
  write_file_atomic(previous.string(), "previous contents\n");
  EXPECT_EQ(facet({"plot", bad, "-o", previous.string()}).exit_code, 1);
  EXPECT_EQ(read_file(previous.string()), "previous contents\n");
}

TEST(PlotCli, HelpTeachesWithExamples) {
  for (const char* cmd : {"plot", "docs"}) {
    ProcessResult r = facet({cmd, "--help"});
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.output.find("Examples:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(std::string("facet ") + cmd + " "), std::string::npos) << r.output;
  }
}

// ---------------------------------------------------------------- facet docs

// Two models through every renderer of the registry (small spheres), with the fixture's cost rows.
TEST(DocsCli, PagesHoldEveryImageAndTheMeasurements) {
  fs::path dir = scratch("full");
  fs::remove_all(dir);
  ProcessResult r = facet({"docs", "-o", dir.string(), "--models", "lambert,phong", "--size", "32", "--cost", kFixture});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 model pages"), std::string::npos) << r.output;
  expect_self_contained(dir);
  for (const char* model : {"lambert", "phong"}) {
    std::string html = read_file((dir / "models" / (std::string(model) + ".html")).string());
    std::vector<std::string> images;
    for (const auto& l : links(html))
      if (l.find(".png") != std::string::npos || l.find(".svg") != std::string::npos) images.push_back(l);
    EXPECT_EQ(images.size(), 2u * 2u + renderer_names().size())
        << model << ": two light angles × (polar, lobe3d) and a sphere per renderer";
    for (const auto& renderer : renderer_names())
      EXPECT_NE(html.find("_single_" + renderer + ".png"), std::string::npos) << model << " " << renderer;
    EXPECT_EQ(count(html, "<span class=pass>pass</span>"), renderer_names().size() - 1)
        << model << ": every renderer but the reference passes";
    EXPECT_NE(html.find("max |Δ|/max(1,|ref|)"), std::string::npos);
  }
  std::string lambert = read_file((dir / "models/lambert.html").string());
  EXPECT_NE(lambert.find("ρ_d = n·l"), std::string::npos) << "the catalog's formula";
  EXPECT_NE(lambert.find("Lambert 1760"), std::string::npos) << "the citation";
  EXPECT_NE(lambert.find("<b>43.6</b>"), std::string::npos) << "the fixture's cost row";
  std::string phong = read_file((dir / "models/phong.html").string());
  EXPECT_NE(phong.find("FIXTURE: the OSL timing run did not finish"), std::string::npos);
  EXPECT_NE(phong.find("exponent; larger is a tighter highlight"), std::string::npos) << "the parameter's doc";
  std::string cost = read_file((dir / "cost.html").string());
  EXPECT_NE(cost.find("fixture_extra"), std::string::npos);
  std::string terms = read_file((dir / "terms.html").string());
  for (const char* term : {"schlick", "v_cavity", "toon", "spot", "inverse_square"})
    EXPECT_NE(terms.find(std::string("<code>") + term + "</code>"), std::string::npos) << term;
}

// Without --cost, the pages carry the cost measured for them (facet cost's
// measure_costs(), read back through its JSON): the path a user takes.
TEST(DocsCli, WithoutCostTheCostIsMeasured) {
  fs::path dir = scratch("measured");
  fs::remove_all(dir);
  ProcessResult r = facet({"docs", "-o", dir.string(), "--models", "lambert", "--size", "16", "--renderers", "reference"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string page = read_file((dir / "models/lambert.html").string());
  EXPECT_EQ(page.find("Not measured"), std::string::npos) << page;
  EXPECT_NE(page.find("SPIR-V instructions: <b>"), std::string::npos) << page;
  std::string cost = read_file((dir / "cost.html").string());
  EXPECT_NE(cost.find("facet cost (measured for these pages)"), std::string::npos);
  EXPECT_NE(cost.find("Glslang"), std::string::npos) << "the tools that measured";
}

TEST(DocsCli, AFailedRendererIsShownWithItsReason) {
  fs::path dir = scratch("failed");
  fs::remove_all(dir);
  ProcessResult r = facet({"docs", "-o", dir.string(), "--models", "lambert", "--size", "16", "--renderers",
                           "reference,osl", "--python", "/nonexistent/python3", "--no-cost"});
  ASSERT_EQ(r.exit_code, 1) << "the pages are written, but a renderer failed: " << r.output;
  EXPECT_NE(r.output.find("0 of 1 renderer comparisons pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("error: 1 of 1 renderer comparisons failed"), std::string::npos) << r.output;
  expect_self_contained(dir);
  std::string page = read_file((dir / "models/lambert.html").string());
  EXPECT_NE(page.find("<span class=fail>FAILED</span> to render"), std::string::npos) << page;
  EXPECT_NE(page.find("/nonexistent/python3"), std::string::npos) << "the reason names the Python that did not run";
  EXPECT_EQ(count(page, "not rendered: left out with --renderers"), renderer_names().size() - 2)
      << "all but the reference and osl";
  EXPECT_NE(page.find("Not measured"), std::string::npos);
  std::string index = read_file((dir / "index.html").string());
  EXPECT_NE(index.find(">failed</td>"), std::string::npos);
  EXPECT_NE(index.find("facet cost --json"), std::string::npos) << "how to get the cost";
  EXPECT_NE(index.find("--no-cost"), std::string::npos) << "why it is not there";
}

TEST(DocsCli, BadInputsNameTheOptionOrFileAndWriteNothing) {
  struct Case {
    std::vector<std::string> args;
    std::string named;
  };
  std::vector<Case> cases = {
      {{"--models", "lambertian"}, "--models: unknown lobe model \"lambertian\" (did you mean \"lambert\"?)"},
      {{"--cost", kBadFixture}, kBadFixture + ": rows[0].glsl.spirv: "},
      {{"--cost", (kSource / "no/cost.json").string()}, "no/cost.json"},
      {{"--renderers", "reference,nosuch"}, "unknown renderer \"nosuch\""},
  };
  for (const auto& c : cases) {
    fs::path dir = scratch("bad");
    fs::remove_all(dir);
    std::vector<std::string> args = {"docs", "-o", dir.string()};
    args.insert(args.end(), c.args.begin(), c.args.end());
    ProcessResult r = facet(args);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(c.named), std::string::npos) << "expected \"" << c.named << "\" in: " << r.output;
    EXPECT_FALSE(fs::exists(dir)) << "nothing is written";
  }
  // A folder that cannot be made is named, not a crash.
  fs::path file = scratch("a_file");
  write_file_atomic(file.string(), "not a folder\n");
  ProcessResult r = facet({"docs", "-o", file.string(), "--models", "lambert", "--no-cost"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(file.string() + "/models: cannot create the folder"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace facet
