// A log–log line chart (chart.h).
#include "docs/chart.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace facet {

namespace {

const Color kInk = Color::hex(0x222222), kGrid = Color::hex(0xdddddd), kMuted = Color::hex(0x777777);

// 1, 10, 100 … as 1, 10, 100, 1k, 10k, 100k, 1M, 10M.
std::string decade_label(int e) {
  if (e < 0) return fmt::format("{:g}", std::pow(10.0, e));
  static const char* suffix[] = {"", "k", "M", "G"};
  int group = std::min(e / 3, 3);
  return fmt::format("{:g}{}", std::pow(10.0, e - 3 * group), suffix[group]);
}

struct Range {
  int lo = 0, hi = 1;  // decades
};

Range decades(const std::vector<ChartSeries>& series, bool x) {
  double lo = INFINITY, hi = 0;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      double v = x ? s.x[i] : s.y[i];
      if (s.x[i] > 0 && s.y[i] > 0) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  if (!(hi > 0)) return {};
  Range r{int(std::floor(std::log10(lo))), int(std::ceil(std::log10(hi)))};
  if (r.hi == r.lo) ++r.hi;
  return r;
}

}  // namespace

Canvas draw_loglog(const LogLogChart& chart) {
  Canvas c(chart.width, chart.height, Color::hex(0xffffff));
  const double left = 62, right = chart.width - 150.0, top = 34, bottom = chart.height - 46.0;
  const Range rx = decades(chart.series, true), ry = decades(chart.series, false);
  auto px = [&](double x) { return left + (std::log10(x) - rx.lo) / (rx.hi - rx.lo) * (right - left); };
  auto py = [&](double y) { return bottom - (std::log10(y) - ry.lo) / (ry.hi - ry.lo) * (bottom - top); };
  c.text({left, 20}, chart.title, {14, kInk, Anchor::Start, true});
  for (int e = rx.lo; e <= rx.hi; ++e) {
    c.polyline({{px(std::pow(10.0, e)), top}, {px(std::pow(10.0, e)), bottom}}, Style::stroked(kGrid, 1));
    c.text({px(std::pow(10.0, e)), bottom + 16}, decade_label(e), {11, kMuted, Anchor::Middle});
  }
  for (int e = ry.lo; e <= ry.hi; ++e) {
    c.polyline({{left, py(std::pow(10.0, e))}, {right, py(std::pow(10.0, e))}}, Style::stroked(kGrid, 1));
    c.text({left - 6, py(std::pow(10.0, e)) + 4}, decade_label(e), {11, kMuted, Anchor::End});
  }
  c.polyline({{left, top}, {left, bottom}, {right, bottom}}, Style::stroked(kInk, 1));
  c.text({(left + right) / 2, double(chart.height) - 10}, chart.x_label, {12, kInk, Anchor::Middle});
  c.text({8, top - 10}, chart.y_label, {12, kInk, Anchor::Start});
  double legend_y = top + 8;
  for (const auto& s : chart.series) {
    std::vector<Point> line;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) line.push_back({px(s.x[i]), py(s.y[i])});
    c.polyline(line, Style::stroked(s.color, 2, s.dashed ? std::vector<double>{6, 4} : std::vector<double>{}));
    for (const auto& p : line) c.circle(p, 3, Style::filled(s.color));
    c.polyline({{right + 14, legend_y - 4}, {right + 34, legend_y - 4}}, Style::stroked(s.color, 2));
    c.text({right + 40, legend_y}, s.label, {11, kInk});
    legend_y += 18;
  }
  if (chart.guide_slope > 0 && !chart.series.empty() && !chart.series[0].x.empty()) {
    // Slope k through the first point: y = y0 (x/x0)^k, to the right edge.
    const double x0 = chart.series[0].x[0], y0 = chart.series[0].y[0];
    const double x1 = std::min(std::pow(10.0, rx.hi), x0 * std::pow(std::pow(10.0, ry.hi) / y0, 1 / chart.guide_slope));
    const double y1 = y0 * std::pow(x1 / x0, chart.guide_slope);
    c.polyline({{px(x0), py(y0)}, {px(x1), py(y1)}}, Style::stroked(kMuted, 1, {2, 3}));
    c.polyline({{right + 14, legend_y - 4}, {right + 34, legend_y - 4}}, Style::stroked(kMuted, 1, {2, 3}));
    c.text({right + 40, legend_y}, fmt::format("slope {:g}{}", chart.guide_slope, chart.guide_slope == 1 ? " (linear)" : ""), {11, kMuted});
  }
  return c;
}

}  // namespace facet
