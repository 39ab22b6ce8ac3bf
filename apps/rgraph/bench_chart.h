// Charts for `rgraph bench`, drawn with cairo: one drawing path onto an SVG
// surface and onto an image surface (antialiased lines, markers and text in
// the fontconfig "sans-serif" face), so both files show the same chart.
//
// A chart for a new bench axis: fill a Chart (title, notes, axis labels), add
// points to series by name (seriesNamed: one colour per series, in the order
// they first appear), and writeChart() it under the run's folder:
//
//   Chart c;
//   c.title = "Bloom: frame time against error";
//   c.xLabel = "PSNR dB";
//   c.yLabel = "frame ms (median)";
//   for (const auto& r : rows) c.seriesNamed(r.method).points.push_back({r.psnr, r.ms, r.variant});
//   writeChart(c, dir, "bloom_ms_vs_error");  // bloom_ms_vs_error.svg and .png
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rgraph::cli::chart {

struct Point {
  double x = 0.0, y = 0.0;
  std::string label;  // drawn beside the marker when non-empty
};

struct Series {
  std::string name;  // legend entry
  std::vector<Point> points;
  bool line = true;     // connect the points in order
  bool markers = true;  // a dot at each point
  bool dashed = false;
  bool hollow = false;  // ring markers instead of dots
  int color = -1;       // index into the palette; -1: the series' index
  double width = 2.0;   // line width in pixels
};

struct Chart {
  std::string title;
  std::string xLabel, yLabel;
  bool logX = false, logY = false;
  std::vector<Series> series;
  std::vector<std::string> notes;  // small lines under the title
  int width = 900, height = 560;

  // The series of that name; a new one (markers, no line: a scatter) when none has it yet.
  Series& seriesNamed(const std::string& name);
};

std::string toSvg(const Chart& chart);
// RGBA8 (opaque), rows top-down, width * height * 4 bytes.
std::vector<uint8_t> toRgba(const Chart& chart);
// Writes NAME.svg and NAME.png under dir; throws RuntimeError on failure.
void writeChart(const Chart& chart, const std::string& dir, const std::string& name);

// Indices of the Pareto-optimal points, sorted by x: no other point is at
// least as good on both axes and better on one. maximizeX / maximizeY say
// which way is better on each axis (e.g. PSNR up, frame time down).
std::vector<size_t> paretoFront(const std::vector<Point>& points, bool maximizeX, bool maximizeY);

}  // namespace rgraph::cli::chart
