// facet — physical checks of every lobe: Helmholtz reciprocity and directional
// albedo (the white furnace), measured on the C++ reference.
//
// The BRDF of a lobe is f(l, v) = ρ(l, v) / (π n·l) (MODELS.md's convention).
//   * Reciprocity: f(l, v) against f(v, l) over random pairs above the horizon;
//     the worst relative difference is reported.
//   * Albedo: a(l) = ∫ f(l, v) (n·v) dω_v over the hemisphere, estimated by
//     Monte Carlo with a one-sample mixture of cosine-distributed directions
//     and mirror directions of GGX half vectors, the width and share picked
//     by a separate pilot run, so that broad and sharp lobes
//     are both estimated well; the standard error comes with each estimate.
// Each lobe is measured white (k = 1) and, where it has a Fresnel term, with
// F = 1: the white furnace. Its numeric parameters are swept (d/4 … 4d around
// the default d, or even steps over a finite range); other choices (geometry
// term, approximation) stay at their defaults, as the catalog's claims are made
// for them. Anisotropic lobes are measured with the light along t and along b.
// Everything is deterministic for a given seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "catalog/catalog.h"

namespace facet {

struct AlbedoEstimate {
  std::string params;  // "alpha 0.2", "" for none
  double theta = 0;    // incidence, degrees from the normal
  double phi = 0;      // azimuth of the light from t, degrees
  double albedo = 0;
  double error = 0;  // one standard error of the estimate
};

struct PhysicsRow {
  const ModelDef* model = nullptr;
  // Reciprocity: the worst |f(l,v) − f(v,l)| / max(f(l,v), f(v,l)).
  double asymmetry = 0;
  bool measured_reciprocal = false;  // asymmetry ≤ kReciprocityTolerance
  bool isotropic = true;             // measured: ρ unchanged when t turns about n
  std::vector<AlbedoEstimate> albedo;
  const AlbedoEstimate& max_albedo() const;
  // Energy conservation holds where no estimate exceeds 1 by more than
  // kSigmas standard errors.
  bool measured_conserving() const;
};

// Relative difference below which f(l, v) and f(v, l) are the same number in
// double precision (the two orders of evaluation round differently).
inline constexpr double kReciprocityTolerance = 1e-9;
inline constexpr double kSigmas = 4;

struct PhysicsOptions {
  std::uint64_t seed = 20261121;
  size_t albedo_samples = 1 << 16;  // per (parameters, θ, φ)
  size_t reciprocity_pairs = 20000;  // per parameter set
  std::vector<double> angles = {0, 30, 60, 75, 85, 89, 89.9};
  int threads = 2;
};

std::vector<PhysicsRow> measure_physics(const PhysicsOptions& options = {});
PhysicsRow measure_physics(const ModelDef& model, const PhysicsOptions& options = {});

// docs/physics.md: the summary table and each model's albedo over θ and its
// parameters, with how they were measured.
std::string physics_markdown(const std::vector<PhysicsRow>& rows, const PhysicsOptions& options);

}  // namespace facet
