// facet — a small 2-D drawing list for the diagrams: filled and stroked shapes
// and text, written out as SVG (by hand: it is text) or rasterised to PNG.
//
// The raster path supersamples every shape (binary coverage per subsample, so
// shapes that share an edge leave no seam), composites it with its opacity, and
// averages the subsamples down; text is drawn with stb_truetype from the same
// font the SVG names (DejaVu Sans), so both files have the same layout.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facet {

struct Point {
  double x = 0, y = 0;  // pixels, y down
};

struct Color {
  uint8_t r = 0, g = 0, b = 0;
  static Color hex(uint32_t rgb) { return {uint8_t(rgb >> 16), uint8_t(rgb >> 8), uint8_t(rgb)}; }
  std::string svg() const;  // "#rrggbb"
};

struct Style {
  bool fill = false;
  Color fill_color;
  double fill_opacity = 1;
  double stroke_width = 0;  // 0: no stroke
  Color stroke_color;
  double stroke_opacity = 1;
  std::vector<double> dash;  // on, off, … lengths in pixels; empty: solid

  static Style filled(Color c, double opacity = 1) {
    Style s;
    s.fill = true;
    s.fill_color = c;
    s.fill_opacity = opacity;
    return s;
  }
  static Style stroked(Color c, double width, std::vector<double> dash = {}) {
    Style s;
    s.stroke_width = width;
    s.stroke_color = c;
    s.dash = std::move(dash);
    return s;
  }
};

enum class Anchor { Start, Middle, End };

struct Text {
  double size = 13;  // em size in pixels (SVG font-size)
  Color color;
  Anchor anchor = Anchor::Start;
  bool bold = false;
};

class Canvas {
 public:
  Canvas(int width, int height, Color background);
  int width() const { return width_; }
  int height() const { return height_; }

  void polygon(std::vector<Point> points, const Style& style);   // closed
  void polyline(std::vector<Point> points, const Style& style);  // open; fill ignored
  void circle(Point centre, double radius, const Style& style);
  void text(Point baseline, const std::string& utf8, const Text& style);

  std::string svg() const;
  // RGB, 8 bits a channel, `supersample`² samples a pixel; throws IoError when
  // there is text and the font cannot be read.
  std::vector<uint8_t> raster(int supersample = 3) const;
  std::string png(int supersample = 3) const;  // the PNG file's bytes

 private:
  enum class Kind { Polygon, Polyline, Circle, Text };
  struct Item {
    Kind kind = Kind::Polygon;
    std::vector<Point> points;  // Circle: {centre, {radius, 0}}; Text: {baseline}
    Style style;
    std::string text;
    Text text_style;
  };
  void add(Kind kind, std::vector<Point> points, const Style& style);
  int width_, height_;
  Color background_;
  std::vector<Item> items_;
};

// Where the font comes from: FACET_FONT at build time (Debian fonts-dejavu-core).
const std::string& font_path();
// Text is UTF-8 with one piece of markup: "_x" or "_{xy}" sets x or xy as a
// subscript (θ_l, k_d), "\_" is an underscore, "\\" a backslash.
// The advance width of a label at `size` in the raster font (for layouts that
// must not overlap; SVG viewers use the same font, so the same width).
double text_width(const std::string& label, double size);
// `s` as a label that shows it as it is (a material's name may hold underscores).
std::string literal(const std::string& s);

}  // namespace facet
