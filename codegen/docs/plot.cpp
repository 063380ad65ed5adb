#include "docs/plot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "catalog/program.h"
#include "core/io.h"
#include "core/vec.h"

namespace facet {

namespace {

double radians(double degrees) { return degrees * kPi / 180; }

const Vec3 kN{0, 0, 1}, kT{1, 0, 0}, kB{0, 1, 0};  // b = n × t

// One palette for both views and the docs' stylesheet: blue diffuse, orange
// specular, the survey's purple light.
const Color kDiffuse = Color::hex(0x3a78c3), kSpecular = Color::hex(0xe07b24), kLight = Color::hex(0x8e44ad);
const Color kInk = Color::hex(0x222222), kMuted = Color::hex(0x666666), kGrid = Color::hex(0xd5d9de);
const Color kSurface = Color::hex(0x333333), kPaper = Color::hex(0xffffff);

Color mix(Color a, Color b, double t) {
  auto m = [t](uint8_t x, uint8_t y) { return uint8_t(std::lround(x + (y - x) * std::clamp(t, 0.0, 1.0))); };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

// The specular share's colour: blue (diffuse) through cream to orange (specular), so
// a half share reads as neither rather than as a muddy grey.
Color share_color(double share, bool surface) {
  Color blue = surface ? Color::hex(0x86b5e8) : kDiffuse, orange = surface ? Color::hex(0xf5a462) : kSpecular;
  Color middle = Color::hex(0xf1ebe0);
  return share < 0.5 ? mix(blue, middle, 2 * share) : mix(middle, orange, 2 * share - 1);
}

Color shade(Color c, double k) {
  auto s = [k](uint8_t x) { return uint8_t(std::lround(std::clamp(x * k, 0.0, 255.0))); };
  return {s(c.r), s(c.g), s(c.b)};
}

std::string number(double v) { return fmt::format("{:.3g}", v); }

// ---------------------------------------------------------------- the radial scale

// The smallest of 1, 2, 2.5 and 5 times a power of ten that is ≥ x: ring steps people read at a glance.
double round_step(double x) {
  double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double mantissa : {1.0, 2.0, 2.5, 5.0})
    if (x <= mantissa * decade * (1 + 1e-9)) return mantissa * decade;
  return 10 * decade;
}

// Value → radius in [0, 1]: linear up to `max`, or `decades` powers of ten below it.
struct RadialScale {
  PlotOptions::Scale kind;
  double max;
  int decades;

  double operator()(double v) const {
    if (!(v > 0)) return 0;
    double r = kind == PlotOptions::Scale::Linear ? v / max : 1 + std::log10(v / max) / decades;
    return std::clamp(r, 0.0, 1.0);
  }
  // The rings drawn and their values: round steps up to `max`, or one a decade.
  std::vector<std::pair<double, double>> rings() const {
    std::vector<std::pair<double, double>> out;
    if (kind == PlotOptions::Scale::Linear) {
      double step = round_step(max / 4);
      for (int k = 1; k * step < max * (1 - 1e-9); ++k) out.push_back({k * step / max, k * step});
      out.push_back({1, max});
    } else {
      for (int k = decades - 1; k >= 0; --k) out.push_back({1 - double(k) / decades, max * std::pow(10.0, -k)});
    }
    return out;
  }
  std::string describe() const {
    if (kind == PlotOptions::Scale::Linear) return fmt::format("linear scale, outer ring = {}", number(max));
    return fmt::format("log scale, a ring per power of ten from {} to {}", number(max * std::pow(10.0, -decades)),
                       number(max));
  }
};

RadialScale scale_for(const PlotOptions& o, double peak) {
  return {o.scale, o.max > 0 ? o.max : plot_scale_max(peak), std::max(1, o.decades)};
}

const Color kLayered = Color::hex(0x2a9d8f);

// What the value is, for the captions.
std::string quantity(const Material& m) {
  return fmt::format("radius: luminance Y (Rec. 709) of k_d⊗ρ_d + k_s⊗ρ_s{} for one white light (the C++ reference), "
                     "views to 89° from n",
                     m.layers.empty() ? "" : " under its layers");
}

std::string lobes_line(const Material& m) {
  std::string s;
  if (m.diffuse) s += "diffuse: " + describe(*m.diffuse);
  if (m.specular) s += (s.empty() ? "" : "  ·  ") + std::string("specular: ") + describe(*m.specular);
  if (!m.layers.empty()) s += fmt::format("  ·  under {} (the legend)", m.layers.size() == 1 ? "a layer" : "layers");
  return s;
}

// The layers, lowest first: "Sheen (roughness = 0.7), then Clear coat (weight = 0.7, …)".
std::string layer_names(const Material& m) {
  std::string s;
  for (const auto& l : m.layers) s += (s.empty() ? "" : ", then ") + describe(l);
  return s;
}

std::string title_of(const Material& m, const PlotOptions& o) {
  return fmt::format("{} — reflected light, θ_l = {}°", literal(o.title.empty() ? m.name : o.title), number(o.light_angle));
}

// ---------------------------------------------------------------- legend

struct LegendItem {
  enum class Mark { Swatch, Line, Dotted, Dashed, Ramp } mark;
  Color color;
  std::string label;
};

constexpr double kLegendSize = 12, kLegendGap = 22, kMarkWidth = 22, kLegendRow = 22;

double item_width(const LegendItem& it) {
  double mark = it.mark == LegendItem::Mark::Ramp ? 2 * kMarkWidth : kMarkWidth;
  return mark + 6 + text_width(it.label, kLegendSize);
}

// The items in rows no wider than `width`.
std::vector<std::vector<LegendItem>> legend_rows(const std::vector<LegendItem>& items, double width) {
  std::vector<std::vector<LegendItem>> rows(1);
  double used = 0;
  for (const auto& it : items) {
    double w = item_width(it) + kLegendGap;
    if (!rows.back().empty() && used + w - kLegendGap > width) {
      rows.push_back({});
      used = 0;
    }
    rows.back().push_back(it);
    used += w;
  }
  return rows;
}

void draw_mark(Canvas& c, const LegendItem& it, double x, double y) {
  switch (it.mark) {
    case LegendItem::Mark::Swatch: {
      Style st = Style::filled(it.color, 0.35);
      st.stroke_width = 1.5;
      st.stroke_color = it.color;
      c.polygon({{x, y - 6}, {x + kMarkWidth, y - 6}, {x + kMarkWidth, y + 6}, {x, y + 6}}, st);
      break;
    }
    case LegendItem::Mark::Line: c.polyline({{x, y}, {x + kMarkWidth, y}}, Style::stroked(it.color, 2.5)); break;
    case LegendItem::Mark::Dotted: c.polyline({{x, y}, {x + kMarkWidth, y}}, Style::stroked(it.color, 1.5, {2, 3})); break;
    case LegendItem::Mark::Dashed: c.polyline({{x, y}, {x + kMarkWidth, y}}, Style::stroked(it.color, 1.2, {5, 3})); break;
    case LegendItem::Mark::Ramp:
      for (int k = 0; k < 8; ++k) {
        double x0 = x + kMarkWidth * 2 * k / 8, x1 = x + kMarkWidth * 2 * (k + 1) / 8;
        c.polygon({{x0, y - 6}, {x1 + 0.5, y - 6}, {x1 + 0.5, y + 6}, {x0, y + 6}},
                  Style::filled(share_color(k / 7.0, false)));
      }
      break;
  }
}

// The legend's rows, centred, the first at `y`.
void legend(Canvas& c, double y, const std::vector<std::vector<LegendItem>>& rows) {
  for (const auto& row : rows) {
    double total = -kLegendGap;
    for (const auto& it : row) total += item_width(it) + kLegendGap;
    double x = (c.width() - total) / 2;
    for (const auto& it : row) {
      draw_mark(c, it, x, y);
      double w = item_width(it);
      c.text({x + w - text_width(it.label, kLegendSize), y + 4}, it.label, {kLegendSize, kInk});
      x += w + kLegendGap;
    }
    y += kLegendRow;
  }
}

std::vector<LegendItem> part_items(const Material& m) {
  std::vector<LegendItem> items;
  if (!m.layers.empty()) {  // a layer weights the lobes' sum as a whole: no parts apart
    items.push_back({LegendItem::Mark::Swatch, kLayered, "under its layers: " + layer_names(m)});
    items.push_back({LegendItem::Mark::Dashed, kLayered, "its lobes alone"});
    return items;
  }
  if (m.diffuse) items.push_back({LegendItem::Mark::Swatch, kDiffuse, "diffuse k_d⊗ρ_d"});
  if (m.specular)
    items.push_back({LegendItem::Mark::Swatch, kSpecular,
                     m.diffuse ? "specular k_s⊗ρ_s (stacked on the diffuse)" : "specular k_s⊗ρ_s"});
  return items;
}

// ---------------------------------------------------------------- polar

// Where the total is largest (the first such sample, or the last with `ties_to_later`).
size_t peak_index(const std::vector<LobeValue>& values, bool ties_to_later) {
  size_t best = 0;
  for (size_t i = 1; i < values.size(); ++i)
    if (values[i].total > values[best].total || (ties_to_later && values[i].total == values[best].total)) best = i;
  return best;
}

// Within 0.1 % of its peak everywhere: a lobe without a direction of its own.
bool flat(const std::vector<LobeValue>& values) {
  double lo = INFINITY, hi = 0;
  for (const auto& v : values) lo = std::min(lo, v.total), hi = std::max(hi, v.total);
  return hi > 0 && lo >= 0.999 * hi;
}

// A point of the plot at view angle θ_v (degrees) and radius r (pixels).
Point polar_point(Point centre, double theta, double r) {
  return {centre.x + r * std::sin(radians(theta)), centre.y - r * std::cos(radians(theta))};
}

std::vector<Point> curve_points(const PolarCurve& c, Point centre, double R, const RadialScale& scale,
                                double LobeValue::*which) {
  std::vector<Point> pts;
  for (size_t i = 0; i < c.angles.size(); ++i) pts.push_back(polar_point(centre, c.angles[i], R * scale(c.values[i].*which)));
  return pts;
}

void polar_grid(Canvas& c, Point centre, double R, const RadialScale& scale) {
  Style grid = Style::stroked(kGrid, 1);
  for (const auto& [r, value] : scale.rings()) {
    std::vector<Point> arc;
    for (int a = -90; a <= 90; a += 2) arc.push_back(polar_point(centre, a, R * r));
    c.polyline(arc, grid);
    c.text({centre.x + R * r, centre.y + 22}, number(value), {11, kMuted, Anchor::Middle});
  }
  for (int a : {-60, -30, 30, 60}) {
    c.polyline({centre, polar_point(centre, a, R)}, grid);
    Point p = polar_point(centre, a, R + 16);
    c.text({p.x, p.y + 4}, fmt::format("{}°", a), {11, kMuted, Anchor::Middle});
  }
  c.text({centre.x - R - 30, centre.y + 4}, "−90°", {11, kMuted, Anchor::Middle});
  c.text({centre.x + R + 30, centre.y + 4}, "90°", {11, kMuted, Anchor::Middle});
  c.text({centre.x, centre.y + 38}, "θ_v: view angle from n (radius: value)", {11, kMuted, Anchor::Middle});
}

void surface(Canvas& c, Point centre, double R) {
  double x0 = centre.x - R - 10, x1 = centre.x + R + 10;
  for (double x = x0 + 4; x < x1; x += 9) c.polyline({{x, centre.y}, {x - 6, centre.y + 7}}, Style::stroked(kMuted, 1));
  c.polyline({{x0, centre.y}, {x1, centre.y}}, Style::stroked(kSurface, 2.5));
}

// n, the light l (arriving: the arrow points at the surface), the angle θ_l, the mirror direction r.
void polar_directions(Canvas& c, Point centre, double R, double theta_l) {
  c.polyline({centre, polar_point(centre, 0, R * 1.02)}, Style::stroked(kMuted, 1.2, {5, 3}));
  c.text({centre.x + 7, centre.y - R * 1.02 + 4}, "n", {13, kInk, Anchor::Start, true});
  if (theta_l >= 1) {
    c.polyline({centre, polar_point(centre, theta_l, R)}, Style::stroked(Color::hex(0x888888), 1.5, {2, 3}));
    Point rp = polar_point(centre, theta_l, R * 0.9);
    c.text({rp.x + 8, rp.y}, "r", {13, kMuted, Anchor::Start, true});
    std::vector<Point> arc;
    for (double a = 0; a >= -theta_l; a -= 1) arc.push_back(polar_point(centre, a, R * 0.2));
    arc.push_back(polar_point(centre, -theta_l, R * 0.2));
    c.polyline(arc, Style::stroked(kLight, 1.2));
    Point lp = polar_point(centre, -theta_l / 2, R * 0.2 + 14);
    c.text({lp.x, lp.y + 4}, "θ_l", {11, kLight, Anchor::Middle});
  }
  Point tip = polar_point(centre, -theta_l, R * 0.03), tail = polar_point(centre, -theta_l, R * 1.02);
  c.polyline({tail, tip}, Style::stroked(kLight, 2.5));
  // Arrowhead at the surface end.
  double dx = tip.x - tail.x, dy = tip.y - tail.y, len = std::hypot(dx, dy);
  dx /= len, dy /= len;
  Point back{tip.x - dx * 12, tip.y - dy * 12};
  c.polygon({tip, {back.x - dy * 5, back.y + dx * 5}, {back.x + dy * 5, back.y - dx * 5}}, Style::filled(kLight));
  // The label beside the line, on the side away from the normal.
  Point lp = polar_point(centre, -theta_l, R * 0.8);
  double a = radians(theta_l);
  c.text({lp.x - 12 * std::cos(a), lp.y + 12 * std::sin(a) + 4}, "l", {13, kLight, Anchor::Middle, true});
}

void polar_panel(Canvas& c, Point centre, double R, const PolarCurve& curve, const RadialScale& scale,
                 double theta_l, const Material& m, const std::string& heading) {
  polar_grid(c, centre, R, scale);
  std::vector<Point> total = curve_points(curve, centre, R, scale, &LobeValue::total);
  std::vector<Point> diffuse = curve_points(curve, centre, R, scale, &LobeValue::diffuse);
  if (!m.layers.empty()) {  // the whole under its layers, and the lobes alone dashed over it
    std::vector<Point> area = total;
    area.push_back(centre);
    c.polygon(area, Style::filled(kLayered, 0.35));
    c.polyline(total, Style::stroked(kLayered, 2));
    c.polyline(curve_points(curve, centre, R, scale, &LobeValue::lobes), Style::stroked(kLayered, 1.5, {5, 3}));
  }
  // The specular part as the band between the diffuse curve and the whole.
  if (m.layers.empty() && m.specular) {
    std::vector<Point> band = total;
    if (m.diffuse) band.insert(band.end(), diffuse.rbegin(), diffuse.rend());
    else band.push_back(centre);
    c.polygon(band, Style::filled(kSpecular, 0.35));
  }
  if (m.layers.empty() && m.diffuse) {
    std::vector<Point> area = diffuse;
    area.push_back(centre);
    c.polygon(area, Style::filled(kDiffuse, 0.35));
  }
  // The whole's outline under the diffuse one: where the specular part is nil, the line is blue.
  if (m.layers.empty() && m.specular) c.polyline(total, Style::stroked(kSpecular, 2));
  if (m.layers.empty() && m.diffuse) c.polyline(diffuse, Style::stroked(kDiffuse, 2));
  surface(c, centre, R);
  polar_directions(c, centre, R, theta_l);
  // The peak, marked and labelled; a lobe the same in every direction (Lambert) has none.
  double peak = curve.peak(), at = curve.peak_angle();
  std::string label = fmt::format("the same {} in every direction", number(peak));
  if (!flat(curve.values)) {
    c.circle(polar_point(centre, at, R * scale(peak)), 3.5, Style::filled(kInk));
    label = fmt::format("peak {} at θ_v = {}°{}", number(peak), number(at), peak > scale.max ? " (clipped)" : "");
  }
  c.text({centre.x + R + 40, centre.y - R - 26}, label, {12, kInk, Anchor::End});
  if (!heading.empty()) c.text({centre.x - R - 40, centre.y - R - 26}, heading, {13, kInk, Anchor::Start, true});
}

// ---------------------------------------------------------------- lobe3d

// An orthographic camera looking at the origin from `toward` (unit, from the origin to the eye).
struct View3 {
  Vec3 toward, right, up;
  Point centre;
  double scale;
  Point project(const Vec3& p) const { return {centre.x + scale * dot(p, right), centre.y - scale * dot(p, up)}; }
  double depth(const Vec3& p) const { return dot(p, toward); }  // larger is nearer the eye
};

View3 oblique_view(Point centre, double scale) {
  // From the front right and above: t runs right and towards the eye, b away to the right,
  // so a lobe stretched along b is seen across, not end-on.
  double az = radians(-30), el = radians(24);
  Vec3 toward{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  Vec3 right = normalize(cross(-toward, kN));
  Vec3 up = cross(right, -toward);
  return {toward, right, up, centre, scale};
}

// What the painter's algorithm sorts: a lobe quad (filled, shaded, its wire
// edges) or a piece of an axis line.
struct Piece3 {
  double depth;
  std::vector<Vec3> corners;     // quad: 4; line piece: 2
  Color color;
  double width = 0;              // line pieces
  std::vector<std::pair<int, int>> wires;  // quad edges on the contour grid
};

void add_line(std::vector<Piece3>& pieces, const View3& view, Vec3 a, Vec3 b, Color color, double width) {
  const int n = 48;
  for (int i = 0; i < n; ++i) {
    Vec3 p = a + (b - a) * (double(i) / n), q = a + (b - a) * (double(i + 1) / n);
    pieces.push_back({view.depth((p + q) * 0.5), {p, q}, color, width, {}});
  }
}

// The lobe surface: r(ω) · ω, one quad per grid cell, lit by a key light over the eye's shoulder.
// `layered`: one colour (a layer weights the lobes' sum as a whole, so no part has a share).
void add_lobe(std::vector<Piece3>& pieces, const View3& view, const LobeMesh& mesh, const RadialScale& scale,
              bool layered) {
  Vec3 key = normalize(view.toward * 0.8 + view.up * 0.6 - view.right * 0.35);
  auto at = [&](int i, int j) {
    size_t k = size_t(i) * size_t(mesh.segments) + size_t(j);
    return mesh.directions[k] * scale(mesh.values[k].total);
  };
  auto share = [&](int i, int j) {
    const LobeValue& v = mesh.values[size_t(i) * size_t(mesh.segments) + size_t(j)];
    return v.total > 0 ? std::clamp(v.specular() / v.total, 0.0, 1.0) : 0.0;
  };
  // Contour lines every 10° of θ and 20° of φ, as the survey's wireframe.
  int ring_step = std::max(1, int(std::lround(10 / (kMaxViewAngle / (mesh.rings - 1)))));
  int segment_step = std::max(1, int(std::lround(20 / (360.0 / (mesh.segments - 1)))));
  for (int i = 0; i + 1 < mesh.rings; ++i)
    for (int j = 0; j + 1 < mesh.segments; ++j) {
      Vec3 p00 = at(i, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1), p10 = at(i + 1, j);
      Vec3 centroid = (p00 + p01 + p11 + p10) * 0.25;
      Vec3 normal = cross(p10 - p00, p01 - p00) + cross(p01 - p11, p10 - p11);
      if (length(normal) < 1e-12) normal = mesh.directions[size_t(i) * size_t(mesh.segments) + size_t(j)];
      // The surface is star-shaped about the origin, so its outward normal has a positive
      // dot with the position; seen from above (its open base faces down) every face turned
      // away from the eye is hidden behind one turned towards it, and is left out.
      normal = normalize(normal);
      if (dot(normal, centroid) < 0) normal = -normal;
      if (dot(normal, view.toward) < 0) continue;
      double light = 0.32 + 0.68 * std::max(0.0, dot(normal, key));
      double s = (share(i, j) + share(i, j + 1) + share(i + 1, j + 1) + share(i + 1, j)) / 4;
      Piece3 q{view.depth(centroid), {p00, p01, p11, p10}, shade(layered ? kLayered : share_color(s, true), light), 0, {}};
      if (i % ring_step == 0) q.wires.push_back({0, 1});
      if ((i + 1) % ring_step == 0) q.wires.push_back({3, 2});
      if (j % segment_step == 0) q.wires.push_back({0, 3});
      if ((j + 1) % segment_step == 0) q.wires.push_back({1, 2});
      pieces.push_back(std::move(q));
    }
}

// The surface under the lobe: a disc of radius 1 (the scale's top value), rings and the t and b axes.
void lobe_floor(Canvas& c, const View3& view) {
  auto ring = [&](double r) {
    std::vector<Point> pts;
    for (int a = 0; a < 360; a += 3) pts.push_back(view.project({r * std::cos(radians(a)), r * std::sin(radians(a)), 0}));
    return pts;
  };
  Style disc = Style::filled(Color::hex(0xeef1f5));
  disc.stroke_width = 1.2;
  disc.stroke_color = Color::hex(0xb9c0ca);
  c.polygon(ring(1), disc);
  c.polygon(ring(0.5), Style::stroked(kGrid, 1));
  for (const auto& [axis, label] : {std::pair<Vec3, const char*>{kT, "t"}, {kB, "b = n × t"}}) {
    c.polyline({view.project(axis * -1.12), view.project(axis * 1.12)}, Style::stroked(Color::hex(0x9aa3ae), 1.2));
    Point p = view.project(axis * 1.2);
    c.text({p.x, p.y + 4}, label, {13, kMuted, Anchor::Middle, true});
  }
}

void draw_pieces(Canvas& c, const View3& view, std::vector<Piece3>& pieces) {
  std::stable_sort(pieces.begin(), pieces.end(), [](const Piece3& a, const Piece3& b) { return a.depth < b.depth; });
  Style wire = Style::stroked(Color::hex(0x1d2b3a), 0.7);
  wire.stroke_opacity = 0.45;
  for (const Piece3& p : pieces) {
    std::vector<Point> pts;
    for (const Vec3& v : p.corners) pts.push_back(view.project(v));
    if (p.corners.size() == 2) {
      c.polyline(pts, Style::stroked(p.color, p.width));
      continue;
    }
    c.polygon(pts, Style::filled(p.color));
    for (const auto& [a, b] : p.wires) c.polyline({pts[size_t(a)], pts[size_t(b)]}, wire);
  }
}

// Title and the caption lines every diagram carries; returns where the drawing may start.
double header(Canvas& c, const Material& m, const PlotOptions& o, const std::string& scale_text) {
  c.text({20, 28}, title_of(m, o), {17, kInk, Anchor::Start, true});
  c.text({20, 48}, literal(lobes_line(m)), {12, kMuted});
  c.text({20, 66}, quantity(m), {12, kMuted});
  c.text({20, 84}, scale_text, {12, kMuted});
  return 96;
}

}  // namespace

// ---------------------------------------------------------------- sampling

double luminance(const RGB& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

LobeSampler::LobeSampler(const Material& m) : ref_(m) {
  if (m.diffuse) k_d_ = m.diffuse->at("color").rgb;
  if (!m.layers.empty()) {
    Material lobes = m;
    lobes.layers.clear();
    if (!lobes.coated()) lobes.coat_normal_map.reset();  // what only a layer read
    lobes_ = std::make_shared<const Reference>(lobes);
  }
}

Vec3 LobeSampler::light(double theta_l, const Vec3& axis) {
  return normalize(axis * -std::sin(radians(theta_l)) + kN * std::cos(radians(theta_l)));
}

LobeValue LobeSampler::value(const Vec3& l, const Vec3& v) const {
  ShadingInputs in = shading_inputs(kN, l, v, kT);
  LobeValue out;
  out.total = luminance(ref_.reflectance(in));
  if (lobes_) {
    out.lobes = luminance(lobes_->reflectance(in));
    return out;
  }
  // The diffuse part as reflectance() forms it: k_d ⊗ ρ_d, zero below the horizon.
  if (in.NoL > 0 && in.NoV > 0) {
    RGB rho = ref_.rho_diffuse(in);
    out.diffuse = luminance({k_d_[0] * rho[0], k_d_[1] * rho[1], k_d_[2] * rho[2]});
  }
  return out;
}

double PolarCurve::peak() const { return values.empty() ? 0 : values[peak_index(values, true)].total; }

// A tie goes to the later sample: a symmetric lobe's peak is named on the mirror side.
double PolarCurve::peak_angle() const { return angles.empty() ? 0 : angles[peak_index(values, true)]; }

std::vector<PolarCurve> polar_curves(const Material& m, double light_angle, int samples) {
  const double edge = kMaxViewAngle;
  LobeSampler sampler(m);
  std::vector<PolarCurve> curves;
  if (sampler.anisotropic()) {
    curves.push_back({"plane of n and t", kT, {}, {}});
    curves.push_back({"plane of n and b", kB, {}, {}});
  } else {
    curves.push_back({"plane of incidence", kT, {}, {}});
  }
  for (auto& c : curves) {
    Vec3 l = LobeSampler::light(light_angle, c.axis);
    for (int i = 0; i < samples; ++i) {
      double theta = -edge + 2 * edge * i / (samples - 1);
      Vec3 v = c.axis * std::sin(radians(theta)) + kN * std::cos(radians(theta));
      c.angles.push_back(theta);
      c.values.push_back(sampler.value(l, v));
    }
  }
  return curves;
}

double LobeMesh::peak() const { return values.empty() ? 0 : values[peak_index(values, false)].total; }

Vec3 LobeMesh::peak_direction() const { return directions.empty() ? kN : directions[peak_index(values, false)]; }

LobeMesh lobe_mesh(const Material& m, double light_angle, int rings, int segments) {
  LobeSampler sampler(m);
  LobeMesh mesh;
  mesh.rings = rings;
  mesh.segments = segments;
  Vec3 l = LobeSampler::light(light_angle, kT);
  for (int i = 0; i < rings; ++i) {
    double theta = radians(kMaxViewAngle * i / (rings - 1));
    for (int j = 0; j < segments; ++j) {
      double phi = radians(360.0 * j / (segments - 1));
      Vec3 v{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      mesh.directions.push_back(v);
      mesh.values.push_back(sampler.value(l, v));
    }
  }
  return mesh;
}

double plot_scale_max(double peak) {
  double p = std::isfinite(peak) ? std::max(peak, 1.0) : 1.0;
  double step = round_step(p / 4);
  return step * std::ceil(p / step - 1e-9);
}

// ---------------------------------------------------------------- the diagrams

Canvas polar_plot(const Material& m, const PlotOptions& o) {
  std::vector<PolarCurve> curves = polar_curves(m, o.light_angle);
  double peak = 0;
  for (const auto& c : curves) peak = std::max(peak, c.peak());
  RadialScale scale = scale_for(o, peak);
  const double R = 210, panel = 2 * R + 130;
  const double width = std::max(40 + panel * double(curves.size()), 800.0);
  std::vector<LegendItem> items = part_items(m);
  items.push_back({LegendItem::Mark::Line, kLight, "light l"});
  items.push_back({LegendItem::Mark::Dotted, Color::hex(0x888888), "mirror direction r"});
  items.push_back({LegendItem::Mark::Dashed, kMuted, "normal n"});
  auto rows = legend_rows(items, width - 40);
  const double top = 100, legend_top = top + 34 + R + 70;
  Canvas c(int(width), int(legend_top + kLegendRow * double(rows.size())), kPaper);
  header(c, m, o, scale.describe() + (curves.size() > 1 ? ", the same in both planes" : ""));
  double left = (width - panel * double(curves.size())) / 2;
  for (size_t i = 0; i < curves.size(); ++i) {
    Point centre{left + panel * (double(i) + 0.5), top + 34 + R};
    std::string heading = curves.size() > 1 ? fmt::format("{} (the light in it)", curves[i].plane) : "";
    polar_panel(c, centre, R, curves[i], scale, o.light_angle, m, heading);
  }
  legend(c, legend_top, rows);
  return c;
}

Canvas lobe3d_plot(const Material& m, const PlotOptions& o) {
  // Half-degree rings and one-degree segments: fine enough that flat-shaded quads read as a smooth surface.
  LobeMesh mesh = lobe_mesh(m, o.light_angle, 179, 361);
  RadialScale scale = scale_for(o, mesh.peak());
  std::vector<LegendItem> items = {{LegendItem::Mark::Line, kLight, "light l"}, {LegendItem::Mark::Line, kMuted, "normal n"}};
  items.insert(items.begin(), m.layers.empty() ? LegendItem{LegendItem::Mark::Ramp, kDiffuse,
                                                            "colour: the specular part's share of the value, 0 → 1"}
                                               : LegendItem{LegendItem::Mark::Swatch, kLayered,
                                                            "under its layers: " + layer_names(m)});
  const double width = 800;
  auto rows = legend_rows(items, width - 40);
  Canvas c(int(width), int(640 + kLegendRow * double(rows.size())), kPaper);
  header(c, m, o, scale.describe() + " at radius 1, the disc's rim; contour lines every 10° of θ_v and 20° of φ_v");
  View3 view = oblique_view({width / 2, 440}, 255);
  lobe_floor(c, view);
  std::vector<Piece3> pieces;
  add_lobe(pieces, view, mesh, scale, !m.layers.empty());
  Vec3 l = LobeSampler::light(o.light_angle, kT);
  add_line(pieces, view, {0, 0, 0}, kN * 1.2, kMuted, 1.4);
  add_line(pieces, view, {0, 0, 0}, l * 1.3, kLight, 2.5);
  draw_pieces(c, view, pieces);
  // Labels on top: the ends of n and l, and the peak.
  Point np = view.project(kN * 1.2), lp = view.project(l * 1.3);
  c.text({np.x + 8, np.y + 4}, "n", {13, kInk, Anchor::Start, true});
  c.circle(lp, 4, Style::filled(kLight));
  c.text({lp.x - 10, lp.y - 6}, fmt::format("l (θ_l = {}°)", number(o.light_angle)), {13, kLight, Anchor::End, true});
  Vec3 pd = mesh.peak_direction();
  double theta = std::acos(std::clamp(pd.z, -1.0, 1.0)) * 180 / kPi, phi = std::atan2(pd.y, pd.x) * 180 / kPi;
  std::string peak = flat(mesh.values) ? fmt::format("the same {} in every direction", number(mesh.peak()))
                                       : fmt::format("peak {} at θ_v = {}°, φ_v = {}°{}", number(mesh.peak()), number(theta),
                                                     number(std::fabs(phi) < 0.5 ? 0 : phi),
                                                     mesh.peak() > scale.max ? " (clipped)" : "");
  c.text({width / 2, 606}, peak + "   (φ_v from t towards b; the light is at φ = 180°)", {12, kInk, Anchor::Middle});
  legend(c, 640, rows);
  return c;
}

void write_plot(const Material& m, const PlotOptions& o, const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  bool png = ext == ".png";
  Canvas c = o.view == PlotOptions::View::Polar ? polar_plot(m, o) : lobe3d_plot(m, o);
  write_file_atomic(path, png ? c.png() : c.svg());
}

}  // namespace facet
