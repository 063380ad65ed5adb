// The reflected-light diagrams show what the NVIDIA survey's diagrams show,
// checked on the sampled curves the plots draw: Lambert a half-disc that
// shrinks as cos θ_l, Phong's lobe at the mirror direction, Minnaert (k > 1)
// dark at the limbs, Ward's lobe stretched across the grooves.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/io.h"
#include "docs/canvas.h"
#include "docs/plot.h"
#include "test_support.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

Material lobe(const std::string& section, const std::string& model, std::map<std::string, double> numbers = {}) {
  ModelSpec spec = default_spec(*find_model(section, model));
  for (const auto& [name, v] : numbers) spec.values[name].number = v;
  return lobe_material(spec, model);
}

// The width in degrees of the stretch of samples around the peak where the total is at least half the peak.
double half_maximum_width(const PolarCurve& c) {
  size_t peak = 0;
  for (size_t i = 0; i < c.values.size(); ++i)
    if (c.values[i].total > c.values[peak].total) peak = i;
  size_t lo = peak, hi = peak;
  while (lo > 0 && c.values[lo - 1].total >= c.values[peak].total / 2) --lo;
  while (hi + 1 < c.values.size() && c.values[hi + 1].total >= c.values[peak].total / 2) ++hi;
  return c.angles[hi] - c.angles[lo];
}

TEST(Plot, LambertIsAHalfDiscThatShrinksAsCosThetaL) {
  Material m = lobe("diffuse", "lambert");
  double r0 = 0;
  for (double theta_l : {0.0, 30.0, 60.0}) {
    std::vector<PolarCurve> curves = polar_curves(m, theta_l);
    ASSERT_EQ(curves.size(), 1u);
    // The same radius in every view direction: a half-disc (a hemisphere in 3-D) of radius cos θ_l.
    for (const auto& v : curves[0].values) {
      EXPECT_NEAR(v.total, std::cos(theta_l * kPi / 180), 1e-12);
      EXPECT_EQ(v.diffuse, v.total);
    }
    if (theta_l == 0) r0 = curves[0].peak();
  }
  EXPECT_NEAR(r0 / polar_curves(m, 60)[0].peak(), 2.0, 1e-9) << "cos 0° / cos 60°";
  LobeMesh mesh = lobe_mesh(m, 60);
  for (const auto& v : mesh.values) EXPECT_NEAR(v.total, 0.5, 1e-12);
}

TEST(Plot, PhongPeaksAtTheMirrorDirection) {
  Material m = lobe("specular", "phong");
  for (double theta_l : {0.0, 20.0, 45.0, 60.0}) {
    PolarCurve c = polar_curves(m, theta_l)[0];
    EXPECT_EQ(c.peak_angle(), theta_l) << "the samples are 0.25° apart, so the mirror is one";
    EXPECT_NEAR(c.peak(), 1.0, 1e-12) << "[r·v]^n = 1 at the mirror";
    // Falling on both sides: not a peak at the edge of a rising curve.
    EXPECT_LT(c.values.front().total, 0.5 * c.peak());
  }
  // In 3-D the same: the peak direction is the mirror of l, r = (sin θ_l, 0, cos θ_l).
  Vec3 r = lobe_mesh(m, 45).peak_direction();
  EXPECT_NEAR(std::acos(r.z) * 180 / kPi, 45, 1.0);
  EXPECT_NEAR(r.y, 0, 1e-9);
  EXPECT_GT(r.x, 0);
}

TEST(Plot, TheDiffusePartIsKdRhoAndTheSpecularTheRest) {
  Material m = load_material(FACET_SOURCE_DIR "/examples/materials/phong.json");  // k_d (0.6, 0.1, 0.1), k_s 0.4, n 40
  PolarCurve c = polar_curves(m, 30)[0];
  double kd = luminance({0.6, 0.1, 0.1}) * std::cos(30 * kPi / 180);
  for (size_t i = 0; i < c.angles.size(); ++i) {
    EXPECT_NEAR(c.values[i].diffuse, kd, 1e-12);
    double rv = std::cos((c.angles[i] - 30) * kPi / 180);  // r·v in the plane
    EXPECT_NEAR(c.values[i].specular(), 0.4 * std::pow(std::max(rv, 0.0), 40), 1e-9) << c.angles[i];
  }
}

// A layered material's diagram: the whole under its layers, and its lobes alone beside it. A
// clear coat over Lambert keeps the lobes' value dimmed by 1 − Fc(n·v) and adds its highlight at
// the mirror direction; a sheen over Lambert rises towards the grazing views.
TEST(Plot, ALayeredMaterialIsDrawnUnderItsLayersBesideItsLobesAlone) {
  Material coated = lobe("diffuse", "lambert");
  coated.layers.push_back(default_spec(*find_model("layer", "clearcoat")));
  coated.layers.back().values["roughness"].number = 0.2;
  PolarCurve c = polar_curves(coated, 40)[0];
  for (size_t i = 0; i < c.angles.size(); ++i) {
    EXPECT_EQ(c.values[i].diffuse, 0) << "a layer weights the lobes as a whole: no parts apart";
    EXPECT_NEAR(c.values[i].lobes, std::cos(40 * kPi / 180), 1e-12);  // white Lambert alone
    if (std::fabs(c.angles[i] - 40) > 30) {
      EXPECT_LT(c.values[i].total, c.values[i].lobes) << c.angles[i];
    }
  }
  EXPECT_NEAR(c.peak_angle(), 40, 1.0) << "the coat's highlight at the mirror direction";
  Material velvet = lobe("diffuse", "lambert");
  velvet.layers.push_back(default_spec(*find_model("layer", "sheen")));
  PolarCurve v = polar_curves(velvet, 60)[0];
  EXPECT_GT(std::fabs(v.peak_angle()), 80) << "a sheen peaks at grazing views";
  EXPECT_GT(polar_plot(velvet, PlotOptions{}).width(), 0);
  EXPECT_GT(lobe3d_plot(velvet, PlotOptions{}).width(), 0);
}

TEST(Plot, MinnaertWithKAboveOneDarkensTheLimbs) {
  PolarCurve dark = polar_curves(lobe("diffuse", "minnaert", {{"k", 1.5}}), 30)[0];
  // From the normal towards either horizon the value only falls, to a small fraction at 89°.
  size_t mid = dark.angles.size() / 2;
  ASSERT_EQ(dark.angles[mid], 0.0);
  for (size_t i = mid; i + 1 < dark.values.size(); ++i) EXPECT_LT(dark.values[i + 1].total, dark.values[i].total);
  for (size_t i = mid; i > 0; --i) EXPECT_LT(dark.values[i - 1].total, dark.values[i].total);
  EXPECT_LT(dark.values.back().total, 0.2 * dark.values[mid].total);
  // k < 1 brightens them instead (the full moon): the check tells the two apart.
  PolarCurve bright = polar_curves(lobe("diffuse", "minnaert", {{"k", 0.8}}), 30)[0];
  EXPECT_GT(bright.values.back().total, bright.values[mid].total);
}

TEST(Plot, WardIsStretchedAcrossTheGrooves) {
  for (const char* model : {"ward", "ward_nvidia"}) {
    Material m = lobe("specular", model, {{"alpha_x", 0.1}, {"alpha_y", 0.3}});
    std::vector<PolarCurve> curves = polar_curves(m, 30);
    ASSERT_EQ(curves.size(), 2u) << model;
    EXPECT_EQ(curves[0].plane, "plane of n and t");
    EXPECT_EQ(curves[1].plane, "plane of n and b");
    double along_t = half_maximum_width(curves[0]), along_b = half_maximum_width(curves[1]);
    EXPECT_GT(along_b, 2.5 * along_t) << model << ": widths " << along_t << "° and " << along_b << "°";
    // Over the hemisphere (light in the n–t plane): the half-maximum region spans more of b than of t.
    LobeMesh mesh = lobe_mesh(m, 30);
    double peak = mesh.peak(), t_lo = 1, t_hi = -1, b_lo = 1, b_hi = -1;
    for (size_t i = 0; i < mesh.values.size(); ++i)
      if (mesh.values[i].total >= peak / 2) {
        t_lo = std::min(t_lo, mesh.directions[i].x), t_hi = std::max(t_hi, mesh.directions[i].x);
        b_lo = std::min(b_lo, mesh.directions[i].y), b_hi = std::max(b_hi, mesh.directions[i].y);
      }
    EXPECT_GT(b_hi - b_lo, 2 * (t_hi - t_lo)) << model;
  }
  // Swapping the roughnesses swaps the planes.
  std::vector<PolarCurve> swapped = polar_curves(lobe("specular", "ward", {{"alpha_x", 0.3}, {"alpha_y", 0.1}}), 30);
  EXPECT_GT(half_maximum_width(swapped[0]), 2.5 * half_maximum_width(swapped[1]));
}

TEST(Plot, OnlyModelsThatReadTheTangentGetTwoPlanes) {
  for (const char* model : {"ward", "ward_nvidia", "heidrich_seidel"})
    EXPECT_EQ(polar_curves(lobe("specular", model), 30).size(), 2u) << model;
  for (const char* model : {"phong", "ggx", "cook_torrance"})
    EXPECT_EQ(polar_curves(lobe("specular", model), 30).size(), 1u) << model;
  EXPECT_EQ(polar_curves(lobe("diffuse", "oren_nayar"), 30).size(), 1u);
}

TEST(Plot, TheScaleIsARoundNumberAtLeastOne) {
  EXPECT_EQ(plot_scale_max(0.3), 1.0);
  EXPECT_EQ(plot_scale_max(1.0), 1.0);
  EXPECT_EQ(plot_scale_max(2.83), 3.0);
  EXPECT_EQ(plot_scale_max(7.12), 8.0);
  EXPECT_EQ(plot_scale_max(8.8), 10.0);
  EXPECT_EQ(plot_scale_max(1234), 1500.0);  // steps of 500
  EXPECT_EQ(plot_scale_max(NAN), 1.0);
}

TEST(Plot, ThePngIsTheCanvasSize) {
  for (const char* file : {"lambert", "ward"}) {
    Material m = load_material(std::string(FACET_SOURCE_DIR "/examples/materials/") + file + ".json");
    for (auto view : {PlotOptions::View::Polar, PlotOptions::View::Lobe3d}) {
      PlotOptions o;
      o.view = view;
      Canvas c = view == PlotOptions::View::Polar ? polar_plot(m, o) : lobe3d_plot(m, o);
      fs::path out = test::scratch("plot", std::string(file) + (view == PlotOptions::View::Polar ? "_polar.png" : "_3d.png"));
      write_plot(m, o, out.string());
      Image png = read_png(out.string());
      EXPECT_EQ(png.width, c.width());
      EXPECT_EQ(png.height, c.height());
    }
  }
  // Two planes side by side for Ward: twice the panels.
  PlotOptions o;
  EXPECT_GT(polar_plot(load_material(FACET_SOURCE_DIR "/examples/materials/ward.json"), o).width(),
            polar_plot(load_material(FACET_SOURCE_DIR "/examples/materials/lambert.json"), o).width() + 250);
}

// The rasteriser draws what it is told: a filled square covers its pixels, and the
// background stays elsewhere.
TEST(Canvas, FillsShapesWhereTheyAre) {
  Canvas c(40, 20, Color::hex(0xffffff));
  c.polygon({{10, 5}, {20, 5}, {20, 15}, {10, 15}}, Style::filled(Color::hex(0xff0000)));
  std::vector<uint8_t> px = c.raster(3);
  auto at = [&](int x, int y) { return &px[(size_t(y) * 40 + size_t(x)) * 3]; };
  EXPECT_EQ(at(15, 10)[0], 255);
  EXPECT_EQ(at(15, 10)[1], 0);
  EXPECT_EQ(at(30, 10)[1], 255);
  EXPECT_EQ(at(5, 10)[1], 255);
}

TEST(Canvas, SubscriptsAreMarkupAndLiteralsAreNot) {
  Canvas c(100, 40, Color::hex(0xffffff));
  c.text({5, 20}, "θ_l " + literal("a_b"), {12, Color::hex(0)});
  std::string svg = c.svg();
  EXPECT_NE(svg.find("font-size=\"8.64\">l</tspan>"), std::string::npos) << svg;
  EXPECT_NE(svg.find("a_b"), std::string::npos) << svg;
}

}  // namespace
}  // namespace facet
