// Charts for `rgraph bench`, with no Python and no plotting package: a chart
// is laid out once into a list of shapes (lines, markers, text), which is
// then written as SVG or rasterised into an RGBA8 buffer (anti-aliased lines
// and markers, a built-in 5x7 bitmap font) for a PNG. Both files show the
// same chart.
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
};

std::string toSvg(const Chart& chart);
// RGBA8, rows top-down, width * height * 4 bytes.
std::vector<uint8_t> toRgba(const Chart& chart);
// Writes NAME.svg and NAME.png under dir; throws RuntimeError on failure.
void writeChart(const Chart& chart, const std::string& dir, const std::string& name);

// Indices of the Pareto-optimal points, sorted by x: no other point is at
// least as good on both axes and better on one. maximizeX / maximizeY say
// which way is better on each axis (e.g. PSNR up, frame time down).
std::vector<size_t> paretoFront(const std::vector<Point>& points, bool maximizeX, bool maximizeY);

}  // namespace rgraph::cli::chart
