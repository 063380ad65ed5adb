// The C++ reference of every model against an independent implementation
// written here from the paper: explicit angles where the paper uses them,
// explicit vectors (mirror direction, half vector) where it uses those, and
// Snell's law for Fresnel. 2000 random direction sets per model, relative error
// ≤ 1e-6.
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "catalog/material.h"
#include "reference/interpreter.h"
#include "scene/scene.h"

namespace facet {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 2000;
constexpr double kRelTol = 1e-6;

struct Dirs {
  Vec3 n, l, v, t, b;
};

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return normalize(v);
}

// n anywhere; l and v above the horizon (n·l, n·v ≥ 0.01); t a random unit tangent.
Dirs random_dirs(std::mt19937_64& rng) {
  Dirs d;
  d.n = random_unit(rng);
  auto above = [&] {
    while (true) {
      Vec3 x = random_unit(rng);
      if (dot(x, d.n) >= 0.01) return x;
    }
  };
  d.l = above();
  d.v = above();
  Vec3 r = random_unit(rng);
  d.t = normalize(r - d.n * dot(r, d.n));
  d.b = cross(d.n, d.t);
  return d;
}

double angle(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.0, 1.0)); }
Vec3 half(const Vec3& l, const Vec3& v) { return normalize(l + v); }

// Snell's-law Fresnel for unpolarized light (Born & Wolf), θ the angle of incidence.
double fresnel_snell(double theta, double eta) {
  double st = std::sin(theta) / eta;
  if (st >= 1) return 1.0;
  double tt = std::asin(st);
  if (theta < 1e-9) return std::pow((eta - 1) / (eta + 1), 2);
  double s = std::sin(theta - tt) / std::sin(theta + tt);
  double p = std::tan(theta - tt) / std::tan(theta + tt);
  return 0.5 * (s * s + p * p);
}

// Runs `closed` against the reference for a material with one lobe of white colour.
void check(const std::string& lobe, const json& spec, const std::function<RGB(const Dirs&)>& closed,
           bool anisotropic = false, uint64_t seed = 1) {
  json doc = {{lobe, spec}};
  Material m = parse_material(doc, "test:" + spec["model"].get<std::string>());
  Reference ref(m);
  std::mt19937_64 rng(seed);
  int compared = 0;
  double worst = 0;
  for (int i = 0; i < kSamples; ++i) {
    Dirs d = random_dirs(rng);
    RGB got = anisotropic ? ref.reflectance(d.n, d.l, d.v, d.t) : ref.reflectance(d.n, d.l, d.v);
    if (!anisotropic) {
      d.t = tangent_rule(d.n, Vec3(m.tangent_axis));
      d.b = cross(d.n, d.t);
    }
    RGB want = closed(d);
    for (int c = 0; c < 3; ++c) {
      double err = std::fabs(got[c] - want[c]) / std::max(std::fabs(want[c]), 1e-9);
      worst = std::max(worst, err);
      ASSERT_LE(err, kRelTol) << spec.dump() << " sample " << i << " channel " << c << ": reference " << got[c]
                              << ", closed form " << want[c] << " (n·l " << dot(d.n, d.l) << ", n·v "
                              << dot(d.n, d.v) << ")";
    }
    ++compared;
  }
  EXPECT_EQ(compared, kSamples);
  ::testing::Test::RecordProperty("worst_relative_error", std::to_string(worst));
}

RGB grey(double x) { return {x, x, x}; }

// ---------------------------------------------------------------- diffuse

TEST(ClosedForm, Lambert) {
  // Lambert: radiance ∝ cos θ_i.
  check("diffuse", {{"model", "lambert"}}, [](const Dirs& d) { return grey(std::cos(angle(d.n, d.l))); });
}

TEST(ClosedForm, Minnaert) {
  // Minnaert 1941: I ∝ cos^k(i) · cos^(k−1)(e).
  for (double k : {0.5, 0.8, 1.0, 1.7}) {
    check("diffuse", {{"model", "minnaert"}, {"k", k}}, [k](const Dirs& d) {
      double ci = std::cos(angle(d.n, d.l)), ce = std::cos(angle(d.n, d.v));
      return grey(std::pow(ci, k) * std::pow(std::max(ce, 1e-4), k - 1));
    });
  }
}

TEST(ClosedForm, MinnaertVelvet) {
  for (double k : {0.0, 0.4, 1.0}) {
    check("diffuse", {{"model", "minnaert_velvet"}, {"k", k}}, [k](const Dirs& d) {
      double ci = std::cos(angle(d.n, d.l)), ce = std::cos(angle(d.n, d.v));
      return grey(std::pow(ci, k + 1) * std::pow(1 - ce, 1 - k));
    });
  }
}

TEST(ClosedForm, OrenNayar) {
  // Oren & Nayar 1994, the qualitative model with explicit angles and azimuths.
  for (bool inter : {false, true}) {
    for (double sigma : {0.0, 0.3, 0.9}) {
      check("diffuse", {{"model", "oren_nayar"}, {"sigma", sigma}, {"interreflection", inter}},
            [sigma, inter](const Dirs& d) {
              double s2 = sigma * sigma;
              double A = 1 - 0.5 * s2 / (s2 + (inter ? 0.57 : 0.33));
              double B = 0.45 * s2 / (s2 + 0.09);
              double ti = angle(d.n, d.l), tr = angle(d.n, d.v);
              double phi_i = std::atan2(dot(d.l, d.b), dot(d.l, d.t));
              double phi_r = std::atan2(dot(d.v, d.b), dot(d.v, d.t));
              double alpha = std::max(ti, tr), beta = std::min(ti, tr);
              double c = std::max(0.0, std::cos(phi_r - phi_i));
              return grey(std::cos(ti) * (A + B * c * std::sin(alpha) * std::tan(beta)));
            });
    }
  }
}

// ---------------------------------------------------------------- classic specular

TEST(ClosedForm, Phong) {
  for (double n : {1.0, 10.0, 60.0}) {
    check("specular", {{"model", "phong"}, {"n", n}}, [n](const Dirs& d) {
      Vec3 r = d.n * (2 * dot(d.n, d.l)) - d.l;  // the mirror direction
      return grey(std::pow(std::max(0.0, dot(r, d.v)), n));
    });
  }
}

TEST(ClosedForm, PhongSchlick) {
  check("specular", {{"model", "phong"}, {"n", 20}, {"approximation", "schlick"}}, [](const Dirs& d) {
    Vec3 r = d.n * (2 * dot(d.n, d.l)) - d.l;
    double t = std::max(0.0, dot(r, d.v));
    return grey(t / (20 - 20 * t + t));
  });
}

TEST(ClosedForm, BlinnPhong) {
  for (double n : {1.0, 50.0, 500.0}) {
    check("specular", {{"model", "blinn_phong"}, {"n", n}},
          [n](const Dirs& d) { return grey(std::pow(std::cos(angle(d.n, half(d.l, d.v))), n)); });
  }
}

TEST(ClosedForm, BlinnPhongSchlick) {
  check("specular", {{"model", "blinn_phong"}, {"n", 80}, {"approximation", "schlick"}}, [](const Dirs& d) {
    double t = dot(d.n, half(d.l, d.v));
    return grey(t / (80 - 80 * t + t));
  });
}

TEST(ClosedForm, Gaussian) {
  for (double m : {5.0, 60.0}) {
    check("specular", {{"model", "gaussian"}, {"m", m}}, [m](const Dirs& d) {
      double th = angle(d.n, half(d.l, d.v));
      return grey(std::exp(-m * th * th));
    });
  }
}

TEST(ClosedForm, HeidrichSeidel) {
  // With α = ∠(l, t), β = ∠(v, t): ρ = [sin α sin β − cos α cos β]^n.
  check(
      "specular", {{"model", "heidrich_seidel"}, {"n", 30}},
      [](const Dirs& d) {
        double a = angle(d.l, d.t), b = angle(d.v, d.t);
        return grey(std::pow(std::max(0.0, std::sin(a) * std::sin(b) - std::cos(a) * std::cos(b)), 30));
      },
      true);
}

// ---------------------------------------------------------------- microfacet

double beckmann_D(double theta_h, double m) {
  double c = std::cos(theta_h), t = std::tan(theta_h);
  return std::exp(-(t * t) / (m * m)) / (kPi * m * m * std::pow(c, 4));
}

double v_cavity(const Dirs& d) {
  Vec3 h = half(d.l, d.v);
  double nh = dot(d.n, h), vh = dot(d.v, h);
  return std::min({1.0, 2 * nh * dot(d.n, d.v) / vh, 2 * nh * dot(d.n, d.l) / vh});
}

// Walter et al. 2007, eq. 34 with tan θ: G1 = 2 / (1 + √(1 + α² tan²θ)).
double smith_G1(double theta, double a) {
  double t = std::tan(theta);
  return 2 / (1 + std::sqrt(1 + a * a * t * t));
}

TEST(ClosedForm, Beckmann) {
  check("specular", {{"model", "beckmann"}, {"m", 0.3}}, [](const Dirs& d) {
    double th = angle(d.n, half(d.l, d.v));
    return grey(kPi * beckmann_D(th, 0.3) / (4 * std::cos(angle(d.n, d.v))));
  });
  check("specular", {{"model", "beckmann"}, {"m", 0.5}, {"geometry", "smith_ggx"}}, [](const Dirs& d) {
    double th = angle(d.n, half(d.l, d.v));
    double G = smith_G1(angle(d.n, d.l), 0.5) * smith_G1(angle(d.n, d.v), 0.5);
    return grey(kPi * beckmann_D(th, 0.5) * G / (4 * std::cos(angle(d.n, d.v))));
  });
}

TEST(ClosedForm, CookTorrance) {
  // Seed 000's form: D = exp(−(tan β/m)²)/(4 m² cos⁴β), R = F D G / (π (n·l)(n·v)); ρ = π R (n·l).
  for (double m : {0.15, 0.4}) {
    check("specular", {{"model", "cook_torrance"}, {"m", m}}, [m](const Dirs& d) {
      Vec3 h = half(d.l, d.v);
      double beta = angle(d.n, h);
      double D = std::exp(-std::pow(std::tan(beta) / m, 2)) / (4 * m * m * std::pow(std::cos(beta), 4));
      double F = fresnel_snell(angle(d.v, h), 1.5);
      double R = F * D * v_cavity(d) / (kPi * dot(d.n, d.l) * dot(d.n, d.v));
      return grey(kPi * R * dot(d.n, d.l));
    });
  }
}

TEST(ClosedForm, CookTorranceSchlickColoured) {
  const RGB f0 = {1.0, 0.78, 0.34};
  check("specular",
        {{"model", "cook_torrance"}, {"m", 0.2}, {"geometry", "smith_ggx"},
         {"fresnel", {{"model", "schlick"}, {"f0", {f0[0], f0[1], f0[2]}}}}},
        [f0](const Dirs& d) {
          Vec3 h = half(d.l, d.v);
          double D = beckmann_D(angle(d.n, h), 0.2);
          double G = smith_G1(angle(d.n, d.l), 0.2) * smith_G1(angle(d.n, d.v), 0.2);
          double x = 1 - std::cos(angle(d.v, h));
          RGB out;
          for (int c = 0; c < 3; ++c) {
            double F = f0[c] + (1 - f0[c]) * std::pow(x, 5);
            out[c] = kPi * D * G * F / (4 * dot(d.n, d.v));
          }
          return out;
        });
}

TEST(ClosedForm, Ggx) {
  // Walter et al. 2007 eq. 33: D = α² / (π cos⁴θ_m (α² + tan²θ_m)²).
  for (double a : {0.05, 0.3, 0.8}) {
    check("specular", {{"model", "ggx"}, {"alpha", a}}, [a](const Dirs& d) {
      Vec3 h = half(d.l, d.v);
      double tm = angle(d.n, h);
      double D = a * a / (kPi * std::pow(std::cos(tm), 4) * std::pow(a * a + std::pow(std::tan(tm), 2), 2));
      double G = smith_G1(angle(d.n, d.l), a) * smith_G1(angle(d.n, d.v), a);
      double F = 0.04 + 0.96 * std::pow(1 - std::cos(angle(d.v, h)), 5);
      double fr = D * G * F / (4 * std::cos(angle(d.n, d.l)) * std::cos(angle(d.n, d.v)));
      return grey(kPi * fr * std::cos(angle(d.n, d.l)));
    });
  }
}

TEST(ClosedForm, GgxExactFresnelVCavity) {
  check("specular",
        {{"model", "ggx"}, {"alpha", 0.1}, {"geometry", "v_cavity"}, {"fresnel", {{"model", "exact"}, {"ior", 1.33}}}},
        [](const Dirs& d) {
          Vec3 h = half(d.l, d.v);
          double tm = angle(d.n, h);
          double D = 0.01 / (kPi * std::pow(std::cos(tm), 4) * std::pow(0.01 + std::pow(std::tan(tm), 2), 2));
          double F = fresnel_snell(angle(d.v, h), 1.33);
          return grey(kPi * D * v_cavity(d) * F / (4 * dot(d.n, d.v)));
        });
}

TEST(ClosedForm, ExactFresnelTotalInternalReflection) {
  // η < 1: beyond the critical angle F = 1 (MODELS.md), as Snell's law says.
  check("specular",
        {{"model", "beckmann"}, {"m", 0.4}, {"fresnel", {{"model", "exact"}, {"ior", 0.7}}}},
        [](const Dirs& d) {
          Vec3 h = half(d.l, d.v);
          double F = fresnel_snell(angle(d.v, h), 0.7);
          return grey(kPi * beckmann_D(angle(d.n, h), 0.4) * F / (4 * dot(d.n, d.v)));
        });
}

TEST(ClosedForm, BlinnTrowbridgeReitz) {
  check("specular", {{"model", "blinn"}, {"c", 0.35}}, [](const Dirs& d) {
    Vec3 h = half(d.l, d.v);
    double cb = std::cos(angle(d.n, h)), c2 = 0.35 * 0.35;
    double D = std::pow(c2 / (cb * cb * (c2 - 1) + 1), 2);
    double F = fresnel_snell(angle(d.v, h), 1.5);
    return grey(D * v_cavity(d) * F / std::cos(angle(d.n, d.v)));
  });
}

TEST(ClosedForm, Ward) {
  // Ward 1992 eq. 5: ρ_s / √(cos θ_i cos θ_r) · exp(−tan²δ (cos²φ/αx² + sin²φ/αy²)) / (4π αx αy),
  // δ the half vector's polar angle and φ its azimuth from t.
  for (auto [ax, ay] : {std::pair{0.08, 0.3}, std::pair{0.2, 0.2}, std::pair{0.5, 0.1}}) {
    check(
        "specular", {{"model", "ward"}, {"alpha_x", ax}, {"alpha_y", ay}},
        [ax = ax, ay = ay](const Dirs& d) {
          Vec3 h = half(d.l, d.v);
          double delta = angle(d.n, h);
          double phi = std::atan2(dot(h, d.b), dot(h, d.t));
          double ti = angle(d.n, d.l), tr = angle(d.n, d.v);
          double e = std::pow(std::tan(delta), 2) *
                     (std::pow(std::cos(phi) / ax, 2) + std::pow(std::sin(phi) / ay, 2));
          double fr = std::exp(-e) / (4 * kPi * ax * ay * std::sqrt(std::cos(ti) * std::cos(tr)));
          return grey(kPi * fr * std::cos(ti));
        },
        true);
  }
}

TEST(ClosedForm, WardNvidia) {
  check(
      "specular", {{"model", "ward_nvidia"}, {"alpha_x", 0.3}, {"alpha_y", 0.1}},
      [](const Dirs& d) {
        Vec3 h = half(d.l, d.v);
        double ex = dot(h, d.t) / 0.3, ey = dot(h, d.b) / 0.1;
        double nl = dot(d.n, d.l), nv = dot(d.n, d.v);
        return grey(nl / (4 * 0.3 * 0.1 * std::sqrt(nl * nv)) * std::exp(-2 * (ex * ex + ey * ey) / (1 + dot(d.n, h))));
      },
      true);
}

TEST(ClosedForm, TangentRuleFeedsAnisotropy) {
  // Without an explicit tangent the reference uses t = normalize(axis × n).
  check("specular", {{"model", "ward"}, {"alpha_x", 0.1}, {"alpha_y", 0.4}}, [](const Dirs& d) {
    Vec3 t = normalize(cross(Vec3(0, 1, 0), d.n)), b = cross(d.n, t);
    Vec3 h = half(d.l, d.v);
    double ex = dot(h, t) / 0.1, ey = dot(h, b) / 0.4, nh = dot(d.n, h);
    double nl = dot(d.n, d.l), nv = dot(d.n, d.v);
    return grey(nl / (4 * 0.1 * 0.4 * std::sqrt(nl * nv)) * std::exp(-(ex * ex + ey * ey) / (nh * nh)));
  });
}

// ---------------------------------------------------------------- modifiers

TEST(ClosedForm, ToonSmooth) {
  check("diffuse", {{"model", "lambert"}, {"toon", {{"cutoff", 0.5}, {"width", 0.2}}}}, [](const Dirs& d) {
    double x = std::clamp((dot(d.n, d.l) - 0.4) / 0.2, 0.0, 1.0);
    return grey(x * x * (3 - 2 * x));
  });
}

TEST(ClosedForm, ToonHard) {
  check("specular", {{"model", "blinn_phong"}, {"n", 20}, {"toon", {{"cutoff", 0.3}}}},
        [](const Dirs& d) { return grey(std::pow(dot(d.n, half(d.l, d.v)), 20) >= 0.3 ? 1.0 : 0.0); });
}

// ---------------------------------------------------------------- the whole reflectance

TEST(Reflectance, IsKdRhoDPlusKsRhoS) {
  json doc = {{"diffuse", {{"model", "lambert"}, {"color", {0.8, 0.5, 0.3}}}},
              {"specular", {{"model", "phong"}, {"color", {0.2, 0.3, 0.4}}, {"n", 10}}}};
  Reference ref(parse_material(doc, "test"));
  std::mt19937_64 rng(7);
  for (int i = 0; i < kSamples; ++i) {
    Dirs d = random_dirs(rng);
    RGB got = ref.reflectance(d.n, d.l, d.v);
    Vec3 r = d.n * (2 * dot(d.n, d.l)) - d.l;
    double s = std::pow(std::max(0.0, dot(r, d.v)), 10), nl = dot(d.n, d.l);
    RGB want = {0.8 * nl + 0.2 * s, 0.5 * nl + 0.3 * s, 0.3 * nl + 0.4 * s};
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 1e-12 * std::max(1.0, want[c]));
  }
}

TEST(Reflectance, HorizonRuleZeroesBelowTheSurface) {
  json doc = {{"diffuse", {{"model", "oren_nayar"}, {"sigma", 0.4}}}, {"specular", {{"model", "ggx"}, {"alpha", 0.3}}}};
  Reference ref(parse_material(doc, "test"));
  std::mt19937_64 rng(9);
  int zero = 0;
  for (int i = 0; i < kSamples; ++i) {
    Vec3 n = random_unit(rng), l = random_unit(rng), v = random_unit(rng);
    if (dot(n, l) > 0 && dot(n, v) > 0) continue;
    RGB c = ref.reflectance(n, l, v);
    ASSERT_EQ(c[0], 0.0);
    ASSERT_EQ(c[1], 0.0);
    ASSERT_EQ(c[2], 0.0);
    ++zero;
  }
  EXPECT_GT(zero, kSamples / 2);
}

// KHR_lights_punctual's recommended range window, as the extension's README writes it:
// attenuation = max(min(1 − (d/r)⁴, 1), 0) / d², through a scene file's light.
TEST(ClosedForm, InverseSquareRangeIsGltfsWindow) {
  json doc = {{"diffuse", {{"model", "lambert"}}}};
  Reference ref(parse_material(doc, "test"));
  Scene s = parse_scene({{"camera", {{"position", {0, 0, 4}}}},
                         {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}}}},
                         {"lights", {{{"type", "point"},
                                      {"position", {0, 0, 0}},
                                      {"attenuation", {{"model", "inverse_square_range"}, {"range", 2.5}}}}}}},
                        "test");
  const Light& light = s.lights.at(0);
  ASSERT_EQ(light.attenuation.law, Attenuation::Law::InverseSquareRange);
  for (double d : {0.1, 0.5, 1.0, 2.0, 2.49, 2.5, 3.0, 100.0}) {
    const double want = std::max(std::min(1 - std::pow(d / 2.5, 4), 1.0), 0.0) / (d * d);
    EXPECT_NEAR(ref.light_factor(light, Vec3(0, 0, 1), d), want, 1e-15 * std::max(want, 1.0)) << "d = " << d;
  }
}

}  // namespace
}  // namespace facet
