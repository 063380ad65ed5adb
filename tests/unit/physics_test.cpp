// The physical checks have teeth: a lobe that reflects more than it receives,
// or one that is not symmetric, is caught; and the albedo estimator agrees with
// closed forms (Minnaert's, and Beckmann's at normal incidence) within its
// stated error.
#include <cmath>

#include <gtest/gtest.h>

#include "analysis/physics.h"
#include "catalog/catalog.h"

namespace facet {
namespace {

PhysicsOptions quick() {
  PhysicsOptions o;
  o.albedo_samples = 8192;
  o.reciprocity_pairs = 2000;
  o.angles = {0, 45, 80, 89};
  return o;
}

ModelDef variant_of_lambert(const std::string& name, std::function<ir::Expr(LobeContext&)> build) {
  ModelDef d = *find_model("diffuse", "lambert");
  d.name = name;
  d.build = std::move(build);
  return d;
}

TEST(Physics, LambertIsReciprocalAndReflectsExactlyWhatItReceives) {
  PhysicsRow r = measure_physics(*find_model("diffuse", "lambert"), quick());
  EXPECT_TRUE(r.measured_reciprocal) << r.asymmetry;
  EXPECT_TRUE(r.measured_conserving());
  for (const auto& e : r.albedo) EXPECT_NEAR(e.albedo, 1.0, 1e-12) << "θ = " << e.theta;
}

TEST(Physics, ALobeBrighterThanLambertIsNotEnergyConserving) {
  ModelDef bright = variant_of_lambert("bright", [](LobeContext& c) { return c.NoL() * 1.01; });
  PhysicsRow r = measure_physics(bright, quick());
  EXPECT_TRUE(r.measured_reciprocal);
  EXPECT_FALSE(r.measured_conserving()) << r.max_albedo().albedo << " ± " << r.max_albedo().error;
}

TEST(Physics, AnAsymmetricLobeIsNotReciprocal) {
  // f = (1 + n·v) / (2π): symmetric ρ would need (1 + n·l) too.
  ModelDef lopsided = variant_of_lambert("lopsided", [](LobeContext& c) { return c.NoL() * (1.0 + c.NoV()) * 0.5; });
  PhysicsRow r = measure_physics(lopsided, quick());
  EXPECT_FALSE(r.measured_reciprocal);
  EXPECT_GT(r.asymmetry, 0.1);
}

TEST(Physics, AlbedoAgreesWithMinnaertsClosedForm) {
  // f = (n·l)^(k−1) (n·v)^(k−1) / π, so a(θ) = 2 cos(θ)^(k−1) / (k + 1).
  PhysicsRow r = measure_physics(*find_model("diffuse", "minnaert"), quick());
  ASSERT_FALSE(r.albedo.empty());
  for (const auto& e : r.albedo) {
    double k = std::stod(e.params.substr(e.params.find(' ') + 1));
    double exact = 2 * std::pow(std::cos(e.theta * M_PI / 180), k - 1) / (k + 1);
    EXPECT_NEAR(e.albedo, exact, 4 * e.error + 1e-12 * exact) << e.params << ", θ = " << e.theta;
  }
}

TEST(Physics, AlbedoAgreesWithBeckmannsClosedFormAtNormalIncidence) {
  // Without G and F, at l = n: a = ∫ over h with θ_h < 45° of D (n·h) dω_h = 1 − exp(−1/m²),
  // the share of Beckmann facets that reflect into the upper hemisphere.
  PhysicsOptions o = quick();
  o.angles = {0};
  PhysicsRow r = measure_physics(*find_model("specular", "beckmann"), o);
  ASSERT_EQ(r.albedo.size(), 5u);
  for (const auto& e : r.albedo) {
    double m = std::stod(e.params.substr(e.params.find(' ') + 1));
    double exact = 1 - std::exp(-1 / (m * m));
    EXPECT_NEAR(e.albedo, exact, 4 * e.error + 1e-12) << e.params;
    EXPECT_LT(e.error, 0.01) << e.params;
  }
}

TEST(Physics, GgxAgreesWithCatalogClaims) {
  PhysicsRow r = measure_physics(*find_model("specular", "ggx"), quick());
  EXPECT_TRUE(r.measured_reciprocal);
  EXPECT_TRUE(r.measured_conserving()) << r.max_albedo().albedo << " ± " << r.max_albedo().error;
  EXPECT_TRUE(r.isotropic);
  EXPECT_FALSE(measure_physics(*find_model("specular", "ward"), quick()).isotropic);
}

}  // namespace
}  // namespace facet
