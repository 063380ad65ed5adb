// facet — a log–log line chart on the diagrams' canvas (docs/canvas.h): the
// benchmarks' growth plots, where a slope is a growth exponent.
#pragma once

#include <string>
#include <vector>

#include "docs/canvas.h"

namespace facet {

struct ChartSeries {
  std::string label;
  Color color;
  std::vector<double> x, y;  // positive; points where either is not are left out
  bool dashed = false;
};

struct LogLogChart {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  // A reference slope drawn through the first point of the first series (1: linear); 0 for none.
  double guide_slope = 1;
  int width = 560, height = 380;
};

// Decade grid lines and labels, one polyline and marker set per series, a legend.
Canvas draw_loglog(const LogLogChart& chart);

}  // namespace facet
