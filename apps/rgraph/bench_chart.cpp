#include "bench_chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "rgraph/error.h"
#include "rgraph/image.h"

namespace rgraph::cli::chart {
namespace {

// ---------------------------------------------------------------- colours

struct Rgb {
  uint8_t r, g, b;
};
// Colour-blind-friendly (Okabe-Ito), then a few more.
constexpr Rgb kPalette[] = {{0, 114, 178},  {213, 94, 0},   {0, 158, 115},  {204, 121, 167}, {230, 159, 0},
                            {86, 180, 233}, {120, 120, 120}, {160, 60, 60}, {60, 60, 160},   {100, 140, 40}};
constexpr Rgb kBlack{0, 0, 0}, kGrid{225, 225, 225}, kAxis{60, 60, 60}, kText{20, 20, 20}, kNote{90, 90, 90},
    kWhite{255, 255, 255}, kLegendBorder{190, 190, 190};

Rgb paletteColor(int i) {
  const int n = static_cast<int>(std::size(kPalette));
  return kPalette[((i % n) + n) % n];
}

std::string hex(Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

// ---------------------------------------------------------------- 5x7 font
// Columns, bit 0 at the top; ASCII 32..126.
constexpr uint8_t kFont[95][5] = {
    {0x00, 0x00, 0x00, 0x00, 0x00}, {0x00, 0x00, 0x5F, 0x00, 0x00}, {0x00, 0x07, 0x00, 0x07, 0x00},
    {0x14, 0x7F, 0x14, 0x7F, 0x14}, {0x24, 0x2A, 0x7F, 0x2A, 0x12}, {0x23, 0x13, 0x08, 0x64, 0x62},
    {0x36, 0x49, 0x56, 0x20, 0x50}, {0x00, 0x05, 0x03, 0x00, 0x00}, {0x00, 0x1C, 0x22, 0x41, 0x00},
    {0x00, 0x41, 0x22, 0x1C, 0x00}, {0x2A, 0x1C, 0x7F, 0x1C, 0x2A}, {0x08, 0x08, 0x3E, 0x08, 0x08},
    {0x00, 0x50, 0x30, 0x00, 0x00}, {0x08, 0x08, 0x08, 0x08, 0x08}, {0x00, 0x60, 0x60, 0x00, 0x00},
    {0x20, 0x10, 0x08, 0x04, 0x02}, {0x3E, 0x51, 0x49, 0x45, 0x3E}, {0x00, 0x42, 0x7F, 0x40, 0x00},
    {0x42, 0x61, 0x51, 0x49, 0x46}, {0x21, 0x41, 0x45, 0x4B, 0x31}, {0x18, 0x14, 0x12, 0x7F, 0x10},
    {0x27, 0x45, 0x45, 0x45, 0x39}, {0x3C, 0x4A, 0x49, 0x49, 0x30}, {0x01, 0x71, 0x09, 0x05, 0x03},
    {0x36, 0x49, 0x49, 0x49, 0x36}, {0x06, 0x49, 0x49, 0x29, 0x1E}, {0x00, 0x36, 0x36, 0x00, 0x00},
    {0x00, 0x56, 0x36, 0x00, 0x00}, {0x08, 0x14, 0x22, 0x41, 0x00}, {0x14, 0x14, 0x14, 0x14, 0x14},
    {0x00, 0x41, 0x22, 0x14, 0x08}, {0x02, 0x01, 0x51, 0x09, 0x06}, {0x32, 0x49, 0x79, 0x41, 0x3E},
    {0x7E, 0x11, 0x11, 0x11, 0x7E}, {0x7F, 0x49, 0x49, 0x49, 0x36}, {0x3E, 0x41, 0x41, 0x41, 0x22},
    {0x7F, 0x41, 0x41, 0x22, 0x1C}, {0x7F, 0x49, 0x49, 0x49, 0x41}, {0x7F, 0x09, 0x09, 0x09, 0x01},
    {0x3E, 0x41, 0x49, 0x49, 0x7A}, {0x7F, 0x08, 0x08, 0x08, 0x7F}, {0x00, 0x41, 0x7F, 0x41, 0x00},
    {0x20, 0x40, 0x41, 0x3F, 0x01}, {0x7F, 0x08, 0x14, 0x22, 0x41}, {0x7F, 0x40, 0x40, 0x40, 0x40},
    {0x7F, 0x02, 0x0C, 0x02, 0x7F}, {0x7F, 0x04, 0x08, 0x10, 0x7F}, {0x3E, 0x41, 0x41, 0x41, 0x3E},
    {0x7F, 0x09, 0x09, 0x09, 0x06}, {0x3E, 0x41, 0x51, 0x21, 0x5E}, {0x7F, 0x09, 0x19, 0x29, 0x46},
    {0x46, 0x49, 0x49, 0x49, 0x31}, {0x01, 0x01, 0x7F, 0x01, 0x01}, {0x3F, 0x40, 0x40, 0x40, 0x3F},
    {0x1F, 0x20, 0x40, 0x20, 0x1F}, {0x3F, 0x40, 0x38, 0x40, 0x3F}, {0x63, 0x14, 0x08, 0x14, 0x63},
    {0x07, 0x08, 0x70, 0x08, 0x07}, {0x61, 0x51, 0x49, 0x45, 0x43}, {0x00, 0x7F, 0x41, 0x41, 0x00},
    {0x02, 0x04, 0x08, 0x10, 0x20}, {0x00, 0x41, 0x41, 0x7F, 0x00}, {0x04, 0x02, 0x01, 0x02, 0x04},
    {0x40, 0x40, 0x40, 0x40, 0x40}, {0x00, 0x01, 0x02, 0x04, 0x00}, {0x20, 0x54, 0x54, 0x54, 0x78},
    {0x7F, 0x48, 0x44, 0x44, 0x38}, {0x38, 0x44, 0x44, 0x44, 0x20}, {0x38, 0x44, 0x44, 0x48, 0x7F},
    {0x38, 0x54, 0x54, 0x54, 0x18}, {0x08, 0x7E, 0x09, 0x01, 0x02}, {0x0C, 0x52, 0x52, 0x52, 0x3E},
    {0x7F, 0x08, 0x04, 0x04, 0x78}, {0x00, 0x44, 0x7D, 0x40, 0x00}, {0x20, 0x40, 0x44, 0x3D, 0x00},
    {0x7F, 0x10, 0x28, 0x44, 0x00}, {0x00, 0x41, 0x7F, 0x40, 0x00}, {0x7C, 0x04, 0x18, 0x04, 0x78},
    {0x7C, 0x08, 0x04, 0x04, 0x78}, {0x38, 0x44, 0x44, 0x44, 0x38}, {0x7C, 0x14, 0x14, 0x14, 0x08},
    {0x08, 0x14, 0x14, 0x18, 0x7C}, {0x7C, 0x08, 0x04, 0x04, 0x08}, {0x48, 0x54, 0x54, 0x54, 0x20},
    {0x04, 0x3F, 0x44, 0x40, 0x20}, {0x3C, 0x40, 0x40, 0x20, 0x7C}, {0x1C, 0x20, 0x40, 0x20, 0x1C},
    {0x3C, 0x40, 0x30, 0x40, 0x3C}, {0x44, 0x28, 0x10, 0x28, 0x44}, {0x0C, 0x50, 0x50, 0x50, 0x3C},
    {0x44, 0x64, 0x54, 0x4C, 0x44}, {0x00, 0x08, 0x36, 0x41, 0x00}, {0x00, 0x00, 0x7F, 0x00, 0x00},
    {0x00, 0x41, 0x36, 0x08, 0x00}, {0x08, 0x04, 0x08, 0x10, 0x08},
};
constexpr int kGlyphAdvance = 6;  // 5 columns + 1 of spacing, times the text scale

// ---------------------------------------------------------------- shapes

enum class Anchor { start, middle, end };

struct Shape {
  enum class Kind { line, circle, rect, text } kind = Kind::line;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // line ends; rect corners; circle/text position
  double r = 0, width = 1;
  Rgb color{0, 0, 0};
  Rgb fill{255, 255, 255};
  bool dashed = false, hollow = false, filled = true;
  std::string text;
  int scale = 2;  // text: pixels per font pixel (glyph cell 6*scale x 7*scale)
  Anchor anchor = Anchor::start;
  bool vertical = false;  // text rotated 90 degrees counter-clockwise
};

double textWidth(const std::string& s, int scale) {
  return s.empty() ? 0.0 : (static_cast<double>(s.size()) * kGlyphAdvance - 1.0) * scale;
}

Shape line(double x0, double y0, double x1, double y1, Rgb c, double w, bool dashed = false) {
  Shape s;
  s.kind = Shape::Kind::line;
  s.x0 = x0, s.y0 = y0, s.x1 = x1, s.y1 = y1, s.color = c, s.width = w, s.dashed = dashed;
  return s;
}
Shape circle(double x, double y, double r, Rgb c, bool hollow, double w = 1.5) {
  Shape s;
  s.kind = Shape::Kind::circle;
  s.x0 = x, s.y0 = y, s.r = r, s.color = c, s.hollow = hollow, s.width = w;
  return s;
}
Shape rect(double x0, double y0, double x1, double y1, Rgb stroke, Rgb fill) {
  Shape s;
  s.kind = Shape::Kind::rect;
  s.x0 = x0, s.y0 = y0, s.x1 = x1, s.y1 = y1, s.color = stroke, s.fill = fill;
  return s;
}
Shape text(double x, double y, std::string str, int scale, Rgb c, Anchor a = Anchor::start, bool vertical = false) {
  Shape s;
  s.kind = Shape::Kind::text;
  s.x0 = x, s.y0 = y, s.text = std::move(str), s.scale = scale, s.color = c, s.anchor = a, s.vertical = vertical;
  return s;
}

// ---------------------------------------------------------------- axes

struct Axis {
  bool log = false;
  double lo = 0, hi = 1;           // data range shown (log: the values, not their logs)
  std::vector<double> ticks;       // values
  double step = 0;                 // linear: tick spacing; log: 0
  double map(double v, double p0, double p1) const {  // value -> pixel between p0 (lo) and p1 (hi)
    const double a = log ? std::log10(lo) : lo, b = log ? std::log10(hi) : hi;
    const double t = ((log ? std::log10(std::max(v, 1e-300)) : v) - a) / (b - a);
    return p0 + t * (p1 - p0);
  }
};

double niceStep(double span, int targetTicks) {
  const double raw = span / std::max(targetTicks, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

Axis makeAxis(std::vector<double> values, bool log, int targetTicks) {
  Axis ax;
  ax.log = log;
  if (log) values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !(v > 0.0); }), values.end());
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  if (values.empty()) values = log ? std::vector<double>{1.0, 10.0} : std::vector<double>{0.0, 1.0};
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  if (log) {
    double a = std::floor(std::log10(lo)), b = std::ceil(std::log10(hi));
    if (b <= a) b = a + 1;
    ax.lo = std::pow(10.0, a);
    ax.hi = std::pow(10.0, b);
    const bool fine = b - a <= 2;
    for (double e = a; e <= b + 1e-9; e += 1.0) {
      const double d = std::pow(10.0, e);
      ax.ticks.push_back(d);
      if (fine && e < b) {
        ax.ticks.push_back(2 * d);
        ax.ticks.push_back(5 * d);
      }
    }
    return ax;
  }
  if (hi - lo < 1e-12) {
    const double pad = std::max(std::abs(lo) * 0.1, 1.0);
    lo -= pad;
    hi += pad;
  }
  const double step = niceStep(hi - lo, targetTicks);
  ax.step = step;
  ax.lo = std::floor(lo / step) * step;
  ax.hi = std::ceil(hi / step) * step;
  for (double v = ax.lo; v <= ax.hi + step * 1e-6; v += step) ax.ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return ax;
}

// A tick value with as many decimals as the tick step needs (step 0: log axes).
std::string tickLabel(double v, double step) {
  char buf[32];
  const double a = std::abs(v);
  if (a == 0.0) return "0";
  if (a >= 1e6 || a < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.0e", v);
  } else if (step > 0.0) {
    const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  } else {
    std::snprintf(buf, sizeof buf, "%g", v);
  }
  return buf;
}

// ---------------------------------------------------------------- layout

std::vector<Shape> layout(const Chart& c) {
  std::vector<Shape> out;
  const double W = c.width, H = c.height;
  // Legend width from the longest name.
  double legendW = 0;
  for (const auto& s : c.series) legendW = std::max(legendW, textWidth(s.name, 2));
  legendW = legendW > 0 ? legendW + 56 : 0;
  const double top = 46 + 12.0 * c.notes.size();
  const double left = 92, bottom = H - 62, right = W - 24 - legendW;

  out.push_back(rect(0, 0, W, H, kWhite, kWhite));
  out.push_back(text(W / 2, 20, c.title, 2, kText, Anchor::middle));
  for (size_t i = 0; i < c.notes.size(); ++i) out.push_back(text(W / 2, 40 + 12.0 * i, c.notes[i], 1, kNote, Anchor::middle));

  std::vector<double> xs, ys;
  for (const auto& s : c.series)
    for (const auto& p : s.points) {
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
  const Axis ax = makeAxis(xs, c.logX, 7), ay = makeAxis(ys, c.logY, 6);
  auto X = [&](double v) { return ax.map(v, left, right); };
  auto Y = [&](double v) { return ay.map(v, bottom, top); };

  for (double t : ax.ticks) {
    const double x = X(t);
    out.push_back(line(x, top, x, bottom, kGrid, 1));
    out.push_back(line(x, bottom, x, bottom + 5, kAxis, 1));
    out.push_back(text(x, bottom + 16, tickLabel(t, ax.step), 2, kText, Anchor::middle));
  }
  for (double t : ay.ticks) {
    const double y = Y(t);
    out.push_back(line(left, y, right, y, kGrid, 1));
    out.push_back(line(left - 5, y, left, y, kAxis, 1));
    out.push_back(text(left - 9, y, tickLabel(t, ay.step), 2, kText, Anchor::end));
  }
  out.push_back(line(left, bottom, right, bottom, kAxis, 1.5));
  out.push_back(line(left, top, left, bottom, kAxis, 1.5));
  out.push_back(text((left + right) / 2, H - 20, c.xLabel + (c.logX ? " (log)" : ""), 2, kText, Anchor::middle));
  out.push_back(text(20, (top + bottom) / 2, c.yLabel + (c.logY ? " (log)" : ""), 2, kText, Anchor::middle, true));

  auto inside = [&](const Point& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && (!c.logX || p.x > 0) && (!c.logY || p.y > 0);
  };
  // Point labels go where they overlap no other label (tried beside the
  // marker, above and below, right then left), else they are left out.
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> placed;
  std::vector<Shape> labels;  // drawn over every series
  auto placeLabel = [&](double px, double py, const std::string& label) {
    const double w = textWidth(label, 1), h = 9;
    const double candidates[][2] = {{7, -9}, {7, 9}, {-7 - w, -9}, {-7 - w, 9}, {7, -19}, {7, 19}};
    for (const auto& d : candidates) {
      const Box b{px + d[0], py + d[1] - h / 2, px + d[0] + w, py + d[1] + h / 2};
      if (b.x0 < left + 2 || b.x1 > right - 2 || b.y0 < top - 10 || b.y1 > bottom) continue;
      bool clash = false;
      for (const Box& o : placed) clash = clash || !(b.x1 < o.x0 || o.x1 < b.x0 || b.y1 < o.y0 || o.y1 < b.y0);
      if (clash) continue;
      placed.push_back(b);
      labels.push_back(rect(b.x0 - 1, b.y0 - 1, b.x1 + 2, b.y1 + 1, kWhite, kWhite));  // keeps lines off the text
      labels.push_back(text(b.x0, py + d[1], label, 1, kText));
      return;
    }
  };
  for (size_t si = 0; si < c.series.size(); ++si) {
    const Series& s = c.series[si];
    const Rgb col = paletteColor(s.color >= 0 ? s.color : static_cast<int>(si));
    const Point* prev = nullptr;
    for (const auto& p : s.points) {
      if (!inside(p)) {
        prev = nullptr;
        continue;
      }
      if (s.line && prev) out.push_back(line(X(prev->x), Y(prev->y), X(p.x), Y(p.y), col, s.width, s.dashed));
      prev = &p;
    }
    for (const auto& p : s.points) {
      if (!inside(p)) continue;
      if (s.markers) out.push_back(circle(X(p.x), Y(p.y), s.hollow ? 6.5 : 3.5, col, s.hollow, 1.8));
      if (!p.label.empty()) placeLabel(X(p.x), Y(p.y), p.label);
    }
  }

  out.insert(out.end(), labels.begin(), labels.end());

  if (legendW > 0) {
    const double lx = right + 16, ly = top;
    out.push_back(rect(lx, ly, lx + legendW, ly + 12 + 22.0 * c.series.size(), kLegendBorder, kWhite));
    for (size_t si = 0; si < c.series.size(); ++si) {
      const Series& s = c.series[si];
      const Rgb col = paletteColor(s.color >= 0 ? s.color : static_cast<int>(si));
      const double y = ly + 17 + 22.0 * si;
      if (s.line) out.push_back(line(lx + 8, y, lx + 38, y, col, s.width, s.dashed));
      if (s.markers) out.push_back(circle(lx + 23, y, s.hollow ? 6.5 : 3.5, col, s.hollow, 1.8));
      out.push_back(text(lx + 46, y, s.name, 2, kText));
    }
  }
  return out;
}

// ---------------------------------------------------------------- SVG

std::string xmlEscape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += ch;
    }
  }
  return o;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// ---------------------------------------------------------------- raster

class Canvas {
 public:
  Canvas(int w, int h) : w_(w), h_(h), px_(static_cast<size_t>(w) * h * 3, 1.0f) {}

  void blend(int x, int y, Rgb c, double a) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_ || a <= 0.0) return;
    a = std::min(a, 1.0);
    float* p = &px_[(static_cast<size_t>(y) * w_ + x) * 3];
    p[0] = static_cast<float>(p[0] * (1 - a) + c.r / 255.0 * a);
    p[1] = static_cast<float>(p[1] * (1 - a) + c.g / 255.0 * a);
    p[2] = static_cast<float>(p[2] * (1 - a) + c.b / 255.0 * a);
  }

  void segment(double x0, double y0, double x1, double y1, Rgb c, double width, bool dashed) {
    const double hw = width / 2;
    const int minX = static_cast<int>(std::floor(std::min(x0, x1) - hw - 1)),
              maxX = static_cast<int>(std::ceil(std::max(x0, x1) + hw + 1));
    const int minY = static_cast<int>(std::floor(std::min(y0, y1) - hw - 1)),
              maxY = static_cast<int>(std::ceil(std::max(y0, y1) + hw + 1));
    const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    for (int y = std::max(minY, 0); y <= std::min(maxY, h_ - 1); ++y)
      for (int x = std::max(minX, 0); x <= std::min(maxX, w_ - 1); ++x) {
        const double px = x + 0.5, py = y + 0.5;
        double t = len2 > 0 ? ((px - x0) * dx + (py - y0) * dy) / len2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        if (dashed && std::fmod(t * len, 12.0) > 7.0) continue;
        const double ex = x0 + t * dx - px, ey = y0 + t * dy - py;
        const double d = std::sqrt(ex * ex + ey * ey);
        blend(x, y, c, std::clamp(hw + 0.5 - d, 0.0, 1.0));
      }
  }

  void disk(double cx, double cy, double r, Rgb c, bool ring, double width) {
    const int minX = static_cast<int>(std::floor(cx - r - width - 1)), maxX = static_cast<int>(std::ceil(cx + r + width + 1));
    const int minY = static_cast<int>(std::floor(cy - r - width - 1)), maxY = static_cast<int>(std::ceil(cy + r + width + 1));
    for (int y = std::max(minY, 0); y <= std::min(maxY, h_ - 1); ++y)
      for (int x = std::max(minX, 0); x <= std::min(maxX, w_ - 1); ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        const double a = ring ? std::clamp(width / 2 + 0.5 - std::abs(d - r), 0.0, 1.0) : std::clamp(r + 0.5 - d, 0.0, 1.0);
        blend(x, y, c, a);
      }
  }

  void fillRect(double x0, double y0, double x1, double y1, Rgb fill, Rgb stroke) {
    const int a = static_cast<int>(std::round(x0)), b = static_cast<int>(std::round(x1));
    const int c = static_cast<int>(std::round(y0)), d = static_cast<int>(std::round(y1));
    for (int y = std::max(c, 0); y < std::min(d, h_); ++y)
      for (int x = std::max(a, 0); x < std::min(b, w_); ++x) {
        const bool edge = x == a || x == b - 1 || y == c || y == d - 1;
        blend(x, y, edge ? stroke : fill, 1.0);
      }
  }

  void glyphs(const Shape& s) {
    const int sc = s.scale;
    const double w = textWidth(s.text, sc);
    double start = s.anchor == Anchor::start ? 0 : s.anchor == Anchor::middle ? -w / 2 : -w;
    const double h = 7.0 * sc;
    for (size_t i = 0; i < s.text.size(); ++i) {
      unsigned char ch = static_cast<unsigned char>(s.text[i]);
      if (ch < 32 || ch > 126) ch = '?';
      const uint8_t* g = kFont[ch - 32];
      for (int col = 0; col < 5; ++col)
        for (int row = 0; row < 7; ++row) {
          if (!((g[col] >> row) & 1)) continue;
          // Position along the text (u) and across it (v, top at 0).
          const double u = start + (static_cast<double>(i) * kGlyphAdvance + col) * sc;
          const double v = row * sc - h / 2;
          for (int a = 0; a < sc; ++a)
            for (int b = 0; b < sc; ++b) {
              int x, y;
              if (s.vertical) {  // rotated 90 degrees counter-clockwise: u goes up, v goes right
                x = static_cast<int>(std::floor(s.x0 + v + b));
                y = static_cast<int>(std::floor(s.y0 - u - a));
              } else {
                x = static_cast<int>(std::floor(s.x0 + u + a));
                y = static_cast<int>(std::floor(s.y0 + v + b));
              }
              blend(x, y, s.color, 1.0);
            }
        }
    }
  }

  std::vector<uint8_t> rgba() const {
    std::vector<uint8_t> out(static_cast<size_t>(w_) * h_ * 4);
    for (size_t i = 0; i < static_cast<size_t>(w_) * h_; ++i) {
      for (int c = 0; c < 3; ++c)
        out[i * 4 + c] = static_cast<uint8_t>(std::lround(std::clamp(px_[i * 3 + c], 0.0f, 1.0f) * 255.0f));
      out[i * 4 + 3] = 255;
    }
    return out;
  }

 private:
  int w_, h_;
  std::vector<float> px_;
};

}  // namespace

std::string toSvg(const Chart& chart) {
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << chart.width << "\" height=\"" << chart.height
    << "\" viewBox=\"0 0 " << chart.width << " " << chart.height << "\">\n";
  o << "<title>" << xmlEscape(chart.title) << "</title>\n";
  for (const Shape& s : layout(chart)) {
    switch (s.kind) {
      case Shape::Kind::line:
        o << "<line x1=\"" << num(s.x0) << "\" y1=\"" << num(s.y0) << "\" x2=\"" << num(s.x1) << "\" y2=\"" << num(s.y1)
          << "\" stroke=\"" << hex(s.color) << "\" stroke-width=\"" << num(s.width) << "\" stroke-linecap=\"round\""
          << (s.dashed ? " stroke-dasharray=\"7 5\"" : "") << "/>\n";
        break;
      case Shape::Kind::circle:
        o << "<circle cx=\"" << num(s.x0) << "\" cy=\"" << num(s.y0) << "\" r=\"" << num(s.r) << "\" ";
        if (s.hollow)
          o << "fill=\"none\" stroke=\"" << hex(s.color) << "\" stroke-width=\"" << num(s.width) << "\"/>\n";
        else
          o << "fill=\"" << hex(s.color) << "\"/>\n";
        break;
      case Shape::Kind::rect:
        o << "<rect x=\"" << num(s.x0) << "\" y=\"" << num(s.y0) << "\" width=\"" << num(s.x1 - s.x0) << "\" height=\""
          << num(s.y1 - s.y0) << "\" fill=\"" << hex(s.fill) << "\" stroke=\"" << hex(s.color) << "\"/>\n";
        break;
      case Shape::Kind::text: {
        const char* anchor = s.anchor == Anchor::start ? "start" : s.anchor == Anchor::middle ? "middle" : "end";
        o << "<text x=\"" << num(s.x0) << "\" y=\"" << num(s.y0) << "\" font-family=\"DejaVu Sans Mono, monospace\" "
          << "font-size=\"" << 10 * s.scale << "\" fill=\"" << hex(s.color) << "\" text-anchor=\"" << anchor
          << "\" dominant-baseline=\"central\"";
        if (s.vertical) o << " transform=\"rotate(-90 " << num(s.x0) << " " << num(s.y0) << ")\"";
        o << ">" << xmlEscape(s.text) << "</text>\n";
        break;
      }
    }
  }
  o << "</svg>\n";
  return o.str();
}

std::vector<uint8_t> toRgba(const Chart& chart) {
  Canvas canvas(chart.width, chart.height);
  for (const Shape& s : layout(chart)) {
    switch (s.kind) {
      case Shape::Kind::line: canvas.segment(s.x0, s.y0, s.x1, s.y1, s.color, s.width, s.dashed); break;
      case Shape::Kind::circle: canvas.disk(s.x0, s.y0, s.r, s.color, s.hollow, s.width); break;
      case Shape::Kind::rect: canvas.fillRect(s.x0, s.y0, s.x1, s.y1, s.fill, s.color); break;
      case Shape::Kind::text: canvas.glyphs(s); break;
    }
  }
  return canvas.rgba();
}

void writeChart(const Chart& chart, const std::string& dir, const std::string& name) {
  const std::filesystem::path base = std::filesystem::path(dir) / name;
  {
    std::ofstream f(base.string() + ".svg");
    if (!f) throw RuntimeError("cannot write '" + base.string() + ".svg'");
    f << toSvg(chart);
    if (!f) throw RuntimeError("cannot write '" + base.string() + ".svg'");
  }
  writePng(base.string() + ".png", static_cast<uint32_t>(chart.width), static_cast<uint32_t>(chart.height),
           toRgba(chart));
}

std::vector<size_t> paretoFront(const std::vector<Point>& points, bool maximizeX, bool maximizeY) {
  auto better = [](double a, double b, bool maximize) { return maximize ? a > b : a < b; };
  auto atLeast = [](double a, double b, bool maximize) { return maximize ? a >= b : a <= b; };
  std::vector<size_t> front;
  for (size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    bool dominated = false;
    for (size_t j = 0; j < points.size() && !dominated; ++j) {
      if (j == i) continue;
      const Point& q = points[j];
      if (!std::isfinite(q.x) || !std::isfinite(q.y)) continue;
      dominated = atLeast(q.x, p.x, maximizeX) && atLeast(q.y, p.y, maximizeY) &&
                  (better(q.x, p.x, maximizeX) || better(q.y, p.y, maximizeY));
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return points[a].x < points[b].x; });
  return front;
}

}  // namespace rgraph::cli::chart
