#include "docs/canvas.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include <fmt/format.h>
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

#include "core/html.h"
#include "core/image.h"
#include "core/io.h"
#include "core/vec.h"

namespace facet {

namespace {

// ---------------------------------------------------------------- text

std::vector<uint32_t> decode_utf8(const std::string& s) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    int extra = c < 0x80 ? 0 : c < 0xE0 ? 1 : c < 0xF0 ? 2 : 3;
    uint32_t cp = extra == 0 ? c : c & (0x3F >> extra);
    for (int k = 1; k <= extra && i + size_t(k) < s.size(); ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    out.push_back(cp);
    i += size_t(extra) + 1;
  }
  return out;
}

struct Font {
  std::string data;
  stbtt_fontinfo info{};
};

// Read once, on first use: a run without text (or without PNG output) never needs it.
const Font& font() {
  static Font f;
  static std::once_flag once;
  std::call_once(once, [] {
    f.data = read_file(font_path());
    if (!stbtt_InitFont(&f.info, reinterpret_cast<const unsigned char*>(f.data.data()), 0))
      throw IoError(font_path() + ": not a TrueType font");
  });
  return f;
}

// Label markup: "_x" or "_{xy}" is a subscript (θ_l, k_d), "\_" an underscore.
struct Run {
  std::string text;
  bool sub = false;
};

std::vector<Run> parse_markup(const std::string& s) {
  std::vector<Run> runs(1);
  auto put = [&](bool sub, const std::string& t) {
    if (runs.back().sub != sub && !runs.back().text.empty()) runs.push_back({});
    runs.back().sub = sub;
    runs.back().text += t;
  };
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size()) {
      put(false, s.substr(++i, 1));
    } else if (s[i] == '_' && i + 1 < s.size() && s[i + 1] == '{' && s.find('}', i) != std::string::npos) {
      size_t end = s.find('}', i);
      put(true, s.substr(i + 2, end - i - 2));
      i = end;
    } else if (s[i] == '_' && i + 1 < s.size()) {
      size_t len = 1;  // one UTF-8 character
      while (i + 1 + len < s.size() && (static_cast<unsigned char>(s[i + 1 + len]) & 0xC0) == 0x80) ++len;
      put(true, s.substr(i + 1, len));
      i += len;
    } else {
      put(false, s.substr(i, 1));
    }
  }
  return runs;
}

constexpr double kSubSize = 0.72, kSubDrop = 0.22;  // a subscript's size and drop, in ems

struct Glyph {
  uint32_t cp;
  double x;      // pen position
  double scale;  // font units → pixels
  bool sub;
};

// Every glyph of the runs at em size `size`, and the total advance.
std::vector<Glyph> layout(const stbtt_fontinfo& info, const std::vector<Run>& runs, double size, double& width) {
  std::vector<Glyph> out;
  double pen = 0;
  for (const Run& run : runs) {
    double scale = stbtt_ScaleForMappingEmToPixels(&info, float(size * (run.sub ? kSubSize : 1)));
    std::vector<uint32_t> cps = decode_utf8(run.text);
    for (size_t i = 0; i < cps.size(); ++i) {
      out.push_back({cps[i], pen, scale, run.sub});
      int advance = 0, bearing = 0;
      stbtt_GetCodepointHMetrics(&info, int(cps[i]), &advance, &bearing);
      pen += advance * scale;
      if (i + 1 < cps.size()) pen += stbtt_GetCodepointKernAdvance(&info, int(cps[i]), int(cps[i + 1])) * scale;
    }
  }
  width = pen;
  return out;
}

// ---------------------------------------------------------------- geometry

std::vector<Point> circle_points(Point c, double r, double pixels_per_unit) {
  int n = std::clamp(int(std::ceil(2 * kPi * r * pixels_per_unit / 2)), 16, 720);
  std::vector<Point> out;
  for (int i = 0; i < n; ++i) {
    double a = 2 * kPi * i / n;
    out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return out;
}

// Splits a polyline into its dashes (on, off, on, … lengths along the line).
std::vector<std::vector<Point>> dashes(const std::vector<Point>& line, const std::vector<double>& pattern) {
  if (pattern.empty()) return {line};
  std::vector<std::vector<Point>> out;
  size_t k = 0;
  double left = pattern[0];
  bool on = true;
  std::vector<Point> current = {line.front()};
  for (size_t i = 1; i < line.size(); ++i) {
    Point a = line[i - 1], b = line[i];
    double len = std::hypot(b.x - a.x, b.y - a.y), done = 0;
    while (len - done > left) {
      done += left;
      Point p{a.x + (b.x - a.x) * done / len, a.y + (b.y - a.y) * done / len};
      if (on) {
        current.push_back(p);
        out.push_back(current);
      }
      current = {p};
      on = !on;
      k = (k + 1) % pattern.size();
      left = pattern[k];
    }
    left -= len - done;
    if (on) current.push_back(b);
  }
  if (on && current.size() > 1) out.push_back(current);
  return out;
}

// The outline of a stroke as convex pieces whose union is the stroke: one quad
// a segment and a disc at each vertex (round joins and caps, as the SVG says).
std::vector<std::vector<Point>> stroke_pieces(const std::vector<Point>& line, double width, double pixels_per_unit) {
  std::vector<std::vector<Point>> out;
  double h = width / 2;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    Point a = line[i], b = line[i + 1];
    double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len == 0) continue;
    double nx = -(b.y - a.y) / len * h, ny = (b.x - a.x) / len * h;
    out.push_back({{a.x + nx, a.y + ny}, {b.x + nx, b.y + ny}, {b.x - nx, b.y - ny}, {a.x - nx, a.y - ny}});
  }
  // Discs only where they show: thin lines need none between collinear-ish segments.
  if (width * pixels_per_unit >= 1.5)
    for (const Point& p : line) out.push_back(circle_points(p, h, pixels_per_unit));
  return out;
}

// ---------------------------------------------------------------- raster

class Raster {
 public:
  Raster(int width, int height, int ss, Color bg) : w_(width * ss), h_(height * ss), ss_(ss), px_(size_t(w_) * size_t(h_) * 3) {
    for (size_t i = 0; i < px_.size(); i += 3) {
      px_[i] = bg.r;
      px_[i + 1] = bg.g;
      px_[i + 2] = bg.b;
    }
  }

  // Union of convex or simple polygons (even–odd each), composited once.
  void fill(const std::vector<std::vector<Point>>& pieces, Color c, double opacity) {
    double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
    for (const auto& piece : pieces)
      for (const Point& p : piece) {
        lo_x = std::min(lo_x, p.x * ss_), hi_x = std::max(hi_x, p.x * ss_);
        lo_y = std::min(lo_y, p.y * ss_), hi_y = std::max(hi_y, p.y * ss_);
      }
    int x0 = std::max(0, int(std::floor(lo_x))), x1 = std::min(w_, int(std::ceil(hi_x)) + 1);
    int y0 = std::max(0, int(std::floor(lo_y))), y1 = std::min(h_, int(std::ceil(hi_y)) + 1);
    if (x0 >= x1 || y0 >= y1) return;
    int bw = x1 - x0;
    std::vector<uint8_t> mask(size_t(bw) * size_t(y1 - y0), 0);
    std::vector<double> xs;
    for (const auto& piece : pieces) {
      for (int y = y0; y < y1; ++y) {
        double sy = (y + 0.5) / ss_;
        xs.clear();
        for (size_t i = 0; i < piece.size(); ++i) {
          Point a = piece[i], b = piece[(i + 1) % piece.size()];
          if ((a.y <= sy) == (b.y <= sy)) continue;  // half-open: a vertex on the line counts once
          xs.push_back((a.x + (sy - a.y) / (b.y - a.y) * (b.x - a.x)) * ss_);
        }
        std::sort(xs.begin(), xs.end());
        for (size_t i = 0; i + 1 < xs.size(); i += 2) {
          int from = std::max(x0, int(std::ceil(xs[i] - 0.5))), to = std::min(x1, int(std::ceil(xs[i + 1] - 0.5)));
          for (int x = from; x < to; ++x) mask[size_t(y - y0) * size_t(bw) + size_t(x - x0)] = 1;
        }
      }
    }
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (mask[size_t(y - y0) * size_t(bw) + size_t(x - x0)]) blend(x, y, c, opacity);
  }

  void text(Point at, const std::string& s, const Text& t) {
    const Font& f = font();
    double size = t.size * ss_, width = 0;
    std::vector<Glyph> glyphs = layout(f.info, parse_markup(s), size, width);
    double x = at.x * ss_ - (t.anchor == Anchor::Middle ? width / 2 : t.anchor == Anchor::End ? width : 0);
    double y = at.y * ss_;
    // No bold face is loaded: a bold label is the regular glyphs drawn twice, offset by a subsample.
    int passes = t.bold ? 2 : 1;
    for (int pass = 0; pass < passes; ++pass)
      for (const Glyph& g : glyphs)
        glyph(f.info, int(g.cp), x + g.x + pass * ss_ * 0.6, y + (g.sub ? kSubDrop * size : 0), g.scale, t.color);
  }

  std::vector<uint8_t> downsample() const {
    int w = w_ / ss_, h = h_ / ss_;
    std::vector<uint8_t> out(size_t(w) * size_t(h) * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          double sum = 0;
          for (int j = 0; j < ss_; ++j)
            for (int i = 0; i < ss_; ++i) sum += px_[(size_t(y * ss_ + j) * size_t(w_) + size_t(x * ss_ + i)) * 3 + size_t(c)];
          out[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)] = uint8_t(std::lround(sum / (ss_ * ss_)));
        }
    return out;
  }

 private:
  void blend(int x, int y, Color c, double a) {
    float* p = &px_[(size_t(y) * size_t(w_) + size_t(x)) * 3];
    p[0] = float(p[0] * (1 - a) + c.r * a);
    p[1] = float(p[1] * (1 - a) + c.g * a);
    p[2] = float(p[2] * (1 - a) + c.b * a);
  }

  void glyph(const stbtt_fontinfo& info, int cp, double pen_x, double baseline, double scale, Color c) {
    float fx = float(pen_x - std::floor(pen_x));
    int x0, y0, x1, y1;
    stbtt_GetCodepointBitmapBoxSubpixel(&info, cp, float(scale), float(scale), fx, 0, &x0, &y0, &x1, &y1);
    int gw = x1 - x0, gh = y1 - y0;
    if (gw <= 0 || gh <= 0) return;
    std::vector<unsigned char> bitmap(size_t(gw) * size_t(gh));
    stbtt_MakeCodepointBitmapSubpixel(&info, bitmap.data(), gw, gh, gw, float(scale), float(scale), fx, 0, cp);
    int ox = int(std::floor(pen_x)) + x0, oy = int(std::lround(baseline)) + y0;
    for (int j = 0; j < gh; ++j)
      for (int i = 0; i < gw; ++i) {
        int x = ox + i, y = oy + j;
        unsigned char v = bitmap[size_t(j) * size_t(gw) + size_t(i)];
        if (v && x >= 0 && y >= 0 && x < w_ && y < h_) blend(x, y, c, v / 255.0);
      }
  }

  int w_, h_, ss_;
  std::vector<float> px_;  // 0–255 per channel, blended in the encoded (sRGB) values, as browsers blend SVG
};

// ---------------------------------------------------------------- SVG

std::string num(double v) {
  std::string s = fmt::format("{:.2f}", v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string svg_points(const std::vector<Point>& pts) {
  std::string s;
  for (const Point& p : pts) s += (s.empty() ? "" : " ") + num(p.x) + "," + num(p.y);
  return s;
}

std::string svg_style(const Style& st, bool closed) {
  std::string s = st.fill && closed ? fmt::format(" fill=\"{}\"", st.fill_color.svg()) : " fill=\"none\"";
  if (st.fill && closed && st.fill_opacity < 1) s += fmt::format(" fill-opacity=\"{}\"", num(st.fill_opacity));
  if (st.fill && closed) s += " fill-rule=\"evenodd\"";
  if (st.stroke_width > 0) {
    s += fmt::format(" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"",
                     st.stroke_color.svg(), num(st.stroke_width));
    if (st.stroke_opacity < 1) s += fmt::format(" stroke-opacity=\"{}\"", num(st.stroke_opacity));
    if (!st.dash.empty()) {
      std::string d;
      for (double x : st.dash) d += (d.empty() ? "" : " ") + num(x);
      s += " stroke-dasharray=\"" + d + "\"";
    }
  }
  return s;
}

// The runs as tspans: a subscript drops and shrinks, the text after it comes back up.
std::string svg_runs(const std::string& label, double size) {
  std::string s;
  bool down = false;
  for (const Run& run : parse_markup(label)) {
    if (run.sub) s += fmt::format("<tspan dy=\"{}\" font-size=\"{}\">", num(kSubDrop * size), num(kSubSize * size));
    else if (down) s += fmt::format("<tspan dy=\"{}\">", num(-kSubDrop * size));
    else s += "<tspan>";
    s += html_escape(run.text) + "</tspan>";
    down = run.sub;
  }
  return s;
}

}  // namespace

std::string Color::svg() const { return fmt::format("#{:02x}{:02x}{:02x}", r, g, b); }

const std::string& font_path() {
  static const std::string path = FACET_FONT;
  return path;
}

double text_width(const std::string& label, double size) {
  double width = 0;
  layout(font().info, parse_markup(label), size, width);
  return width;
}

std::string literal(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '_' || c == '\\') o += '\\';
    o += c;
  }
  return o;
}

Canvas::Canvas(int width, int height, Color background) : width_(width), height_(height), background_(background) {}

void Canvas::add(Kind kind, std::vector<Point> points, const Style& style) {
  Item it;
  it.kind = kind;
  it.points = std::move(points);
  it.style = style;
  items_.push_back(std::move(it));
}

void Canvas::polygon(std::vector<Point> points, const Style& style) {
  if (points.size() >= 2) add(Kind::Polygon, std::move(points), style);
}

void Canvas::polyline(std::vector<Point> points, const Style& style) {
  if (points.size() >= 2) add(Kind::Polyline, std::move(points), style);
}

void Canvas::circle(Point centre, double radius, const Style& style) { add(Kind::Circle, {centre, {radius, 0}}, style); }

void Canvas::text(Point baseline, const std::string& utf8, const Text& style) {
  add(Kind::Text, {baseline}, Style{});
  items_.back().text = utf8;
  items_.back().text_style = style;
}

std::string Canvas::svg() const {
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"{2}\"/>\n",
      width_, height_, background_.svg());
  for (const Item& it : items_) {
    switch (it.kind) {
      case Kind::Polygon:
        s += fmt::format("<polygon points=\"{}\"{}/>\n", svg_points(it.points), svg_style(it.style, true));
        break;
      case Kind::Polyline:
        s += fmt::format("<polyline points=\"{}\"{}/>\n", svg_points(it.points), svg_style(it.style, false));
        break;
      case Kind::Circle:
        s += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}/>\n", num(it.points[0].x), num(it.points[0].y),
                         num(it.points[1].x), svg_style(it.style, true));
        break;
      case Kind::Text: {
        const Text& t = it.text_style;
        const char* anchor = t.anchor == Anchor::Middle ? "middle" : t.anchor == Anchor::End ? "end" : "start";
        s += fmt::format(
            "<text x=\"{}\" y=\"{}\" font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"{}\" "
            "text-anchor=\"{}\"{} fill=\"{}\">{}</text>\n",
            num(it.points[0].x), num(it.points[0].y), num(t.size), anchor, t.bold ? " font-weight=\"bold\"" : "",
            t.color.svg(), svg_runs(it.text, t.size));
        break;
      }
    }
  }
  return s + "</svg>\n";
}

std::vector<uint8_t> Canvas::raster(int supersample) const {
  Raster r(width_, height_, supersample, background_);
  double ppu = supersample;  // subsamples per canvas pixel: how finely curves are flattened
  for (const Item& it : items_) {
    if (it.kind == Kind::Text) {
      r.text(it.points[0], it.text, it.text_style);
      continue;
    }
    const Style& st = it.style;
    std::vector<Point> outline = it.kind == Kind::Circle ? circle_points(it.points[0], it.points[1].x, ppu) : it.points;
    if (st.fill && it.kind != Kind::Polyline) r.fill({outline}, st.fill_color, st.fill_opacity);
    if (st.stroke_width > 0) {
      if (it.kind != Kind::Polyline) outline.push_back(outline.front());
      std::vector<std::vector<Point>> pieces;
      for (const auto& dash : dashes(outline, st.dash))
        for (auto& piece : stroke_pieces(dash, st.stroke_width, ppu)) pieces.push_back(std::move(piece));
      r.fill(pieces, st.stroke_color, st.stroke_opacity);
    }
  }
  return r.downsample();
}

std::string Canvas::png(int supersample) const { return encode_png(width_, height_, raster(supersample), "the diagram"); }

}  // namespace facet
