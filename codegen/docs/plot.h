// facet — the reflected-light diagrams of the NVIDIA survey (Losasso, "Surface
// Reflection Models"): for one white light at incidence θ_l, how much light
// leaves in each view direction.
//
// The plotted value is the survey's I without ambient and attenuation: the
// luminance Y (Rec. 709 weights of linear RGB) of k_d ⊗ ρ_d + k_s ⊗ ρ_s as the
// C++ reference computes it (facet::Reference), split into its diffuse part
// and the whole. The frame is n = +z, t = +x, b = n × t = +y; the light lies in
// the plane drawn, on the negative side, so its mirror direction has the
// positive view angle θ_v = +θ_l.
//
//   polar   the value over view directions in a plane of incidence, as a radius
//           (materials that read the tangent: the plane of n and t and the
//           plane of n and b, side by side);
//   lobe3d  the surface r(ω) = value(ω) over the upper hemisphere, seen from an
//           oblique camera, coloured by the specular part's share.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "core/vec.h"
#include "docs/canvas.h"
#include "reference/interpreter.h"

namespace facet {

struct PlotOptions {
  enum class View { Polar, Lobe3d };
  enum class Scale { Linear, Log };
  double light_angle = 45;  // θ_l: degrees from the normal, in [0, 90)
  View view = View::Polar;
  Scale scale = Scale::Linear;
  // The value of the outer ring (polar) and of radius 1 (lobe3d); 0: plot_scale_max(peak).
  // Diagrams meant to be compared (one material at several θ_l) share one.
  double max = 0;
  int decades = 3;    // log scale: the powers of ten shown below `max`
  std::string title;  // default: the material's name
};

// Y of linear RGB, Rec. 709 weights: the plotted channel.
double luminance(const RGB& c);

// One view direction's value: the luminance of k_d ⊗ ρ_d and of the whole
// (the specular part is their difference).
struct LobeValue {
  // A material with layers: diffuse 0 (a layer weights the lobes' sum as a whole, so the parts
  // are not drawn apart), `lobes` the lobes' k_d⊗ρ_d + k_s⊗ρ_s without the layers.
  double diffuse = 0, total = 0, lobes = 0;
  double specular() const { return total - diffuse; }
};

// Evaluates the diagram's value with the C++ reference in the frame above.
class LobeSampler {
 public:
  explicit LobeSampler(const Material& m);
  const Material& material() const { return ref_.material(); }
  bool anisotropic() const { return ref_.program().uses_tangent(); }
  LobeValue value(const Vec3& l, const Vec3& v) const;
  // The light at θ_l degrees in the plane of n and `axis`, on its negative side.
  static Vec3 light(double theta_l, const Vec3& axis);

 private:
  Reference ref_;
  std::shared_ptr<const Reference> lobes_;  // the material without its layers, where it has some
  RGB k_d_{0, 0, 0};
};

// The views the diagrams sample stop 1° short of the horizon: Ward's 1/√(n·v)
// and the microfacet lobes' 1/(n·v) (without masking) have no bound there,
// and one sample at n·v = 6e-17 would set the scale of the whole plot.
inline constexpr double kMaxViewAngle = 89;

// The value over view angles θ_v ∈ [−89°, 89°] in one plane of incidence.
struct PolarCurve {
  std::string plane;  // "plane of incidence", "plane of n and t", "plane of n and b"
  Vec3 axis;          // the surface direction in the plane: t or b
  std::vector<double> angles;  // θ_v, degrees, positive on the mirror side
  std::vector<LobeValue> values;
  double peak() const;        // the largest total
  double peak_angle() const;  // where it is
};

// What a polar plot draws: one plane of incidence, or for a material that
// reads the tangent the plane containing t and the one containing b. The
// default samples every 0.25°, so whole and quarter degrees (a mirror
// direction θ_v = θ_l) are samples.
std::vector<PolarCurve> polar_curves(const Material& m, double light_angle, int samples = 713);

// The value over the upper hemisphere on a (θ, φ) grid: `rings` rows from
// θ = 0 to kMaxViewAngle, `segments` columns from φ = 0 to 360° (both ends included).
struct LobeMesh {
  int rings = 0, segments = 0;
  std::vector<Vec3> directions;  // row-major: [ring · segments + segment]
  std::vector<LobeValue> values;
  double peak() const;
  Vec3 peak_direction() const;
};
LobeMesh lobe_mesh(const Material& m, double light_angle, int rings = 90, int segments = 181);

// A round number ≥ max(peak, 1) for the outer ring (a multiple of a step of 1,
// 2, 2.5 or 5 times a power of ten): 1 is a white Lambert surface facing the
// light, so lobes of different models compare.
double plot_scale_max(double peak);

Canvas polar_plot(const Material& m, const PlotOptions& o);
Canvas lobe3d_plot(const Material& m, const PlotOptions& o);
// The diagram o.view asks for, written to `path` (.svg or .png; lobe3d: .png),
// whole or not at all.
void write_plot(const Material& m, const PlotOptions& o, const std::string& path);

}  // namespace facet
