#include "bench_chart.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "rgraph/error.h"
#include "rgraph/image.h"
#include "rgraph/output_file.h"

namespace rgraph::cli::chart {
namespace {

struct Rgb {
  double r, g, b;
};
constexpr Rgb rgb(int r, int g, int b) { return {r / 255.0, g / 255.0, b / 255.0}; }
// Colour-blind-friendly (Okabe-Ito), then a few more.
constexpr Rgb kPalette[] = {rgb(0, 114, 178),   rgb(213, 94, 0),  rgb(0, 158, 115), rgb(204, 121, 167),
                            rgb(230, 159, 0),   rgb(86, 180, 233), rgb(120, 120, 120), rgb(160, 60, 60),
                            rgb(60, 60, 160),   rgb(100, 140, 40)};
constexpr Rgb kGrid = rgb(225, 225, 225), kAxis = rgb(60, 60, 60), kText = rgb(20, 20, 20), kNote = rgb(90, 90, 90),
              kWhite = rgb(255, 255, 255), kLegendBorder = rgb(190, 190, 190);
constexpr const char* kFont = "sans-serif";
constexpr double kTickSize = 13, kTitleSize = 16, kNoteSize = 11, kLabelSize = 10.5;

Rgb paletteColor(int i) {
  const int n = static_cast<int>(std::size(kPalette));
  return kPalette[((i % n) + n) % n];
}

// ---------------------------------------------------------------- axes

struct Axis {
  bool log = false;
  double lo = 0, hi = 1;      // data range shown (log: the values, not their logs)
  std::vector<double> ticks;  // values
  double step = 0;            // linear: tick spacing; log: 0
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
  std::erase_if(values, [&](double v) { return !std::isfinite(v) || (log && !(v > 0.0)); });
  if (values.empty()) values = log ? std::vector<double>{1.0, 10.0} : std::vector<double>{0.0, 1.0};
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  if (log) {
    double a = std::floor(std::log10(lo)), b = std::ceil(std::log10(hi));
    if (b <= a) b = a + 1;
    ax.lo = std::pow(10.0, a);
    ax.hi = std::pow(10.0, b);
    for (double e = a; e <= b + 1e-9; e += 1.0) {
      const double d = std::pow(10.0, e);
      ax.ticks.push_back(d);
      if (b - a <= 2 && e < b) ax.ticks.insert(ax.ticks.end(), {2 * d, 5 * d});  // a short range: 1-2-5
    }
    return ax;
  }
  if (hi - lo < 1e-12) {
    const double pad = std::max(std::abs(lo) * 0.1, 1.0);
    lo -= pad;
    hi += pad;
  }
  ax.step = niceStep(hi - lo, targetTicks);
  ax.lo = std::floor(lo / ax.step) * ax.step;
  ax.hi = std::ceil(hi / ax.step) * ax.step;
  for (double v = ax.lo; v <= ax.hi + ax.step * 1e-6; v += ax.step)
    ax.ticks.push_back(std::abs(v) < ax.step * 1e-9 ? 0.0 : v);
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

// ---------------------------------------------------------------- drawing

enum class Align { start, middle, end };

class Pen {
 public:
  explicit Pen(cairo_t* cr) : cr_(cr) {}

  double textWidth(const std::string& s, double size, bool bold = false) const {
    font(size, bold);
    cairo_text_extents_t e;
    cairo_text_extents(cr_, s.c_str(), &e);
    return e.x_advance;
  }
  // Vertically centred on y; vertical: rotated a quarter turn counter-clockwise about (x, y).
  void text(double x, double y, const std::string& s, double size, Rgb c, Align a = Align::start,
            bool vertical = false, bool bold = false) const {
    cairo_save(cr_);
    const double w = textWidth(s, size, bold);
    cairo_font_extents_t fe;
    cairo_font_extents(cr_, &fe);
    cairo_translate(cr_, x, y);
    if (vertical) cairo_rotate(cr_, -M_PI / 2);
    cairo_move_to(cr_, a == Align::start ? 0 : a == Align::middle ? -w / 2 : -w, (fe.ascent - fe.descent) / 2);
    color(c);
    cairo_show_text(cr_, s.c_str());
    cairo_restore(cr_);
  }
  void line(double x0, double y0, double x1, double y1, Rgb c, double width, bool dashed = false) const {
    const double dash[] = {7, 5};
    cairo_set_dash(cr_, dash, dashed ? 2 : 0, 0);
    cairo_move_to(cr_, x0, y0);
    cairo_line_to(cr_, x1, y1);
    stroke(c, width);
  }
  void marker(double x, double y, Rgb c, bool hollow) const {
    cairo_set_dash(cr_, nullptr, 0, 0);
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, x, y, hollow ? 6.5 : 3.5, 0, 2 * M_PI);
    hollow ? stroke(c, 1.8) : fill(c);
  }
  void rect(double x0, double y0, double x1, double y1, Rgb fillColor, const Rgb* border = nullptr) const {
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    if (!border) return fill(fillColor);
    color(fillColor);
    cairo_fill_preserve(cr_);
    cairo_set_dash(cr_, nullptr, 0, 0);
    stroke(*border, 1);
  }

 private:
  void font(double size, bool bold) const {
    cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, size);
  }
  void color(Rgb c) const { cairo_set_source_rgb(cr_, c.r, c.g, c.b); }
  void fill(Rgb c) const {
    color(c);
    cairo_fill(cr_);
  }
  void stroke(Rgb c, double width) const {
    color(c);
    cairo_set_line_width(cr_, width);
    cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
    cairo_stroke(cr_);
  }
  cairo_t* cr_;
};

// Point labels go where they overlap no other label (tried beside the
// marker, above and below, right then left), else they are left out.
class LabelPlacer {
 public:
  LabelPlacer(double left, double top, double right, double bottom) : l_(left), t_(top), r_(right), b_(bottom) {}
  // The top-left corner of a free w x h box near (px, py), taken; none: no room.
  std::optional<std::pair<double, double>> place(double px, double py, double w, double h) {
    const double candidates[][2] = {{7, -10}, {7, 10}, {-7 - w, -10}, {-7 - w, 10}, {7, -21}, {7, 21}};
    for (const auto& d : candidates) {
      const Box b{px + d[0], py + d[1] - h / 2, px + d[0] + w, py + d[1] + h / 2};
      if (b.x0 < l_ + 2 || b.x1 > r_ - 2 || b.y0 < t_ - 10 || b.y1 > b_) continue;
      if (std::any_of(placed_.begin(), placed_.end(), [&](const Box& o) {
            return !(b.x1 < o.x0 || o.x1 < b.x0 || b.y1 < o.y0 || o.y1 < b.y0);
          }))
        continue;
      placed_.push_back(b);
      return std::pair{b.x0, b.y0};
    }
    return std::nullopt;
  }

 private:
  struct Box {
    double x0, y0, x1, y1;
  };
  double l_, t_, r_, b_;
  std::vector<Box> placed_;
};

void draw(cairo_t* cr, const Chart& c) {
  const Pen pen(cr);
  const double W = c.width, H = c.height;
  double legendW = 0;
  for (const auto& s : c.series) legendW = std::max(legendW, pen.textWidth(s.name, kTickSize));
  legendW = legendW > 0 ? legendW + 56 : 0;
  const double top = 50 + 14.0 * c.notes.size();
  const double left = 80, bottom = H - 58, right = W - 24 - legendW;

  pen.rect(0, 0, W, H, kWhite);
  pen.text(W / 2, 20, c.title, kTitleSize, kText, Align::middle, false, true);
  for (size_t i = 0; i < c.notes.size(); ++i)
    pen.text(W / 2, 40 + 14.0 * i, c.notes[i], kNoteSize, kNote, Align::middle);

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
    pen.line(X(t), top, X(t), bottom, kGrid, 1);
    pen.line(X(t), bottom, X(t), bottom + 5, kAxis, 1);
    pen.text(X(t), bottom + 16, tickLabel(t, ax.step), kTickSize, kText, Align::middle);
  }
  for (double t : ay.ticks) {
    pen.line(left, Y(t), right, Y(t), kGrid, 1);
    pen.line(left - 5, Y(t), left, Y(t), kAxis, 1);
    pen.text(left - 9, Y(t), tickLabel(t, ay.step), kTickSize, kText, Align::end);
  }
  pen.line(left, bottom, right, bottom, kAxis, 1.5);
  pen.line(left, top, left, bottom, kAxis, 1.5);
  pen.text((left + right) / 2, H - 20, c.xLabel + (c.logX ? " (log)" : ""), kTickSize, kText, Align::middle);
  pen.text(18, (top + bottom) / 2, c.yLabel + (c.logY ? " (log)" : ""), kTickSize, kText, Align::middle, true);

  auto inside = [&](const Point& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && (!c.logX || p.x > 0) && (!c.logY || p.y > 0);
  };
  auto colorOf = [&](size_t si) { return paletteColor(c.series[si].color >= 0 ? c.series[si].color : int(si)); };
  LabelPlacer placer(left, top, right, bottom);
  std::vector<std::pair<std::pair<double, double>, const std::string*>> labels;  // drawn over every series
  for (size_t si = 0; si < c.series.size(); ++si) {
    const Series& s = c.series[si];
    const Point* prev = nullptr;
    for (const auto& p : s.points) {
      if (s.line && prev && inside(p)) pen.line(X(prev->x), Y(prev->y), X(p.x), Y(p.y), colorOf(si), s.width, s.dashed);
      prev = inside(p) ? &p : nullptr;
    }
    for (const auto& p : s.points) {
      if (!inside(p)) continue;
      if (s.markers) pen.marker(X(p.x), Y(p.y), colorOf(si), s.hollow);
      if (p.label.empty()) continue;
      if (auto at = placer.place(X(p.x), Y(p.y), pen.textWidth(p.label, kLabelSize), kLabelSize + 1))
        labels.push_back({*at, &p.label});
    }
  }
  for (const auto& [at, label] : labels) {
    const double w = pen.textWidth(*label, kLabelSize);
    pen.rect(at.first - 1, at.second - 1, at.first + w + 2, at.second + kLabelSize + 2, kWhite);  // lines off the text
    pen.text(at.first, at.second + (kLabelSize + 1) / 2, *label, kLabelSize, kText);
  }

  if (legendW > 0) {
    const double lx = right + 16, ly = top;
    pen.rect(lx, ly, lx + legendW, ly + 12 + 22.0 * c.series.size(), kWhite, &kLegendBorder);
    for (size_t si = 0; si < c.series.size(); ++si) {
      const Series& s = c.series[si];
      const double y = ly + 17 + 22.0 * si;
      if (s.line) pen.line(lx + 8, y, lx + 38, y, colorOf(si), s.width, s.dashed);
      if (s.markers) pen.marker(lx + 23, y, colorOf(si), s.hollow);
      pen.text(lx + 46, y, s.name, kTickSize, kText);
    }
  }
}

// Draws the chart onto `surface` and finishes it; throws on a cairo error.
void render(cairo_surface_t* surface, const Chart& chart) {
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface), cairo_destroy);
  draw(cr.get(), chart);
  cairo_surface_flush(surface);
  if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
    throw RuntimeError(std::string("drawing chart '") + chart.title + "': " + cairo_status_to_string(cairo_status(cr.get())));
}

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

}  // namespace

std::string toSvg(const Chart& chart) {
  std::string out;
  auto append = [](void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
  };
  Surface s(cairo_svg_surface_create_for_stream(append, &out, chart.width, chart.height), cairo_surface_destroy);
  render(s.get(), chart);
  cairo_surface_finish(s.get());
  return out;
}

std::vector<uint8_t> toRgba(const Chart& chart) {
  Surface s(cairo_image_surface_create(CAIRO_FORMAT_RGB24, chart.width, chart.height), cairo_surface_destroy);
  render(s.get(), chart);
  // RGB24: one native-endian 32-bit word per pixel, 0x00RRGGBB.
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  std::vector<uint8_t> rgba(static_cast<size_t>(chart.width) * chart.height * 4);
  for (int y = 0; y < chart.height; ++y)
    for (int x = 0; x < chart.width; ++x) {
      const uint32_t p = *reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride + 4 * x);
      uint8_t* o = &rgba[(static_cast<size_t>(y) * chart.width + x) * 4];
      o[0] = static_cast<uint8_t>(p >> 16), o[1] = static_cast<uint8_t>(p >> 8), o[2] = static_cast<uint8_t>(p), o[3] = 255;
    }
  return rgba;
}

void writeChart(const Chart& chart, const std::string& dir, const std::string& name) {
  const std::string base = (std::filesystem::path(dir) / name).string();
  writeOutputFile(base + ".svg", toSvg(chart));
  writePng(base + ".png", static_cast<uint32_t>(chart.width), static_cast<uint32_t>(chart.height), toRgba(chart));
}

Series& Chart::seriesNamed(const std::string& name) {
  for (Series& s : series)
    if (s.name == name) return s;
  Series& s = series.emplace_back();
  s.name = name;
  s.line = false;
  return s;
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
      const Point& q = points[j];
      if (j == i || !std::isfinite(q.x) || !std::isfinite(q.y)) continue;
      dominated = atLeast(q.x, p.x, maximizeX) && atLeast(q.y, p.y, maximizeY) &&
                  (better(q.x, p.x, maximizeX) || better(q.y, p.y, maximizeY));
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return points[a].x < points[b].x; });
  return front;
}

}  // namespace rgraph::cli::chart
