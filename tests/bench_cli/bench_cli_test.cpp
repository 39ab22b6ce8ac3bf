// `rgraph bench` end to end (a hidden tiny sweep: 2 points at 64x64, 1 frame
// each; no timing is checked, benchmarks stay out of unit tests), and the
// chart module it draws with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>

#include "../../apps/rgraph/bench_chart.h"

#include "bench_cli/context_json.h"
#include "support/run_command.h"

namespace {
namespace fs = std::filesystem;

// stdout and stderr
using RunResult = rgraph::testsupport::CommandResult;
RunResult run(const std::string& args) {
  return rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " " + args + " 2>&1");
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

uint32_t bigEndian(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rgraph-bench-cli-" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  return dir;
}

TEST(BenchCli, SmokeSweepWritesResultsAndCharts) {
  const fs::path dir = freshDir("smoke");
  const RunResult r = run("bench --smoke --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("results.csv"), std::string::npos) << r.out;

  // CSV: a header and one row per point.
  const std::string csv = slurp(dir / "results.csv");
  ASSERT_FALSE(csv.empty());
  std::istringstream lines(csv);
  std::string header, row;
  std::getline(lines, header);
  for (const char* col : {"method", "layout", "threshold", "lights", "median_ms", "min_ms", "max_ms", "psnr_db",
                          "max_abs_error", "share_over_1", "gbuffer_bytes_per_pixel", "allocated_bytes"})
    EXPECT_NE(header.find(col), std::string::npos) << col;
  int rows = 0;
  while (std::getline(lines, row))
    if (!row.empty()) {
      ++rows;
      EXPECT_NE(row.find(",ok"), std::string::npos) << row;
    }
  EXPECT_EQ(rows, 2);

  // JSON: the same points, each timed and compared with the reference.
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "results.json"));
  ASSERT_EQ(j.at("points").size(), 2u);
  for (const auto& p : j.at("points")) {
    EXPECT_GE(p.at("frames").get<int>(), 1);
    EXPECT_GT(p.at("median_ms").get<double>(), 0.0);
    EXPECT_LE(p.at("min_ms").get<double>(), p.at("max_ms").get<double>());
    EXPECT_GT(p.at("psnr_db").get<double>(), 20.0);  // a lit image close to the reference
    EXPECT_EQ(p.at("width").get<int>(), 64);
    EXPECT_EQ(p.at("gbuffer_bytes_per_pixel").get<int>(), 36);  // the pbr layout with depth
    EXPECT_GT(p.at("allocated_bytes").get<double>(), 0.0);
    EXPECT_FALSE(p.contains("error")) << p.dump();
  }
  // The context it ran on: GL strings and EGL device, as a context of this process sees them.
  const rgraph::ContextDevice device = rgraph::test::thisProcessDevice();
  rgraph::test::expectContextJson(j.at("machine"), device);
  EXPECT_EQ(j.at("machine").at("software"), device.renderer.find("llvmpipe") != std::string::npos) << device.renderer;
  EXPECT_NE(slurp(dir / "figures.md").find("GL_VENDOR " + device.vendor + ", GL_RENDERER " + device.renderer +
                                           ", GL_VERSION " + device.version + "; EGL platform " + device.platform),
            std::string::npos)
      << slurp(dir / "figures.md");

  // Charts: SVG and PNG of each, at the chart's size.
  for (const char* name : {"frame_ms_vs_lights", "frame_ms_vs_error", "bytes_vs_error"}) {
    const std::string svg = slurp(dir / (std::string(name) + ".svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos) << name;
    EXPECT_NE(svg.find("width=\"900pt\" height=\"560pt\""), std::string::npos) << name;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << name;
    const std::string png = slurp(dir / (std::string(name) + ".png"));
    ASSERT_GT(png.size(), 24u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
    EXPECT_EQ(bigEndian(png, 16), 900u) << name;
    EXPECT_EQ(bigEndian(png, 20), 560u) << name;
  }

  // --replot redraws the charts from results.json alone.
  const fs::path again = dir.parent_path() / "replot";
  const RunResult re = run("bench --replot " + (dir / "results.json").string() + " --out " + again.string());
  ASSERT_EQ(re.exitCode, 0) << re.out;
  for (const char* name : {"frame_ms_vs_lights", "frame_ms_vs_error", "bytes_vs_error"})
    EXPECT_EQ(slurp(again / (std::string(name) + ".svg")), slurp(dir / (std::string(name) + ".svg"))) << name;
  fs::remove_all(dir.parent_path());
}

// The exact loop (fullscreen, no cut-off) at every light count, and every
// method's error against it at the same count (--only lights keeps both;
// untimed: only the deterministic figures are checked).
TEST(BenchCli, LightsAxisHasTheExactLoopAtEveryCount) {
  const fs::path dir = freshDir("exact");
  const RunResult r = run("bench --quick --figures-only --only lights --scene learnopengl --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "results.json"));
  std::map<int, nlohmann::json> exact;                      // lights -> the exact row
  std::map<int, std::map<std::string, nlohmann::json>> at;  // lights -> method -> row at the default cut-off
  for (const auto& p : j.at("points")) {
    const auto axes = p.at("axes").get<std::vector<std::string>>();
    const bool isExact = std::count(axes.begin(), axes.end(), "lights_exact") > 0;
    if (isExact) {
      EXPECT_EQ(p.at("method"), "fullscreen");
      EXPECT_EQ(p.at("threshold").get<double>(), 0.0);
      exact[p.at("lights").get<int>()] = p;
    } else {
      EXPECT_NE(std::count(axes.begin(), axes.end(), "lights"), 0) << p.dump();
      at[p.at("lights").get<int>()][p.at("method").get<std::string>()] = p;
    }
  }
  ASSERT_EQ(exact.size(), 4u) << "learnopengl has 32 lights: 1, 4, 16, 32";
  ASSERT_EQ(at.size(), exact.size());
  for (const auto& [n, e] : exact) {
    SCOPED_TRACE("lights " + std::to_string(n));
    // Against itself, and against forward_lit (the G-buffer only): close.
    EXPECT_EQ(e.at("psnr_exact_db").get<double>(), 100.0);
    EXPECT_EQ(e.at("max_abs_error_exact").get<int>(), 0);
    EXPECT_GT(e.at("psnr_db").get<double>(), 45.0);
    ASSERT_EQ(at[n].size(), 8u);
    for (const auto& [method, p] : at[n]) {
      SCOPED_TRACE(method);
      ASSERT_TRUE(p.contains("psnr_exact_db")) << p.dump();
      const double db = p.at("psnr_exact_db").get<double>();
      EXPECT_GT(db, 20.0);  // a lit image of the same scene, not black or another count's
      // The cut-off drops light the exact loop keeps (the far-field methods add it back).
      if (n >= 4 && method.find("_far") == std::string::npos) {
        EXPECT_LT(db, 60.0);
      }
    }
    // The far field recovers part of what the cut-off loses.
    if (n >= 4) {
      for (const char* m : {"tiled", "clustered"})
        EXPECT_GT(at[n][std::string(m) + "_far"].at("psnr_exact_db").get<double>(),
                  at[n][m].at("psnr_exact_db").get<double>() + 1.0)
            << m;
    }
    // The deferred culling methods shade what the fullscreen loop shades at the
    // same cut-off (within 1/255), so they sit at the same distance from it.
    for (const char* m : {"tiled", "clustered"})
      EXPECT_NEAR(at[n][m].at("psnr_exact_db").get<double>(), at[n]["fullscreen"].at("psnr_exact_db").get<double>(),
                  0.5)
          << m;
  }
  // The CSV's columns and the figures table docs/performance.md quotes.
  const std::string csv = slurp(dir / "results.csv");
  EXPECT_NE(csv.substr(0, csv.find('\n')).find("psnr_exact_db,max_abs_error_exact"), std::string::npos);
  const std::string figures = slurp(dir / "figures.md");
  const size_t block = figures.find("<!-- bench-figures:lights_exact -->");
  ASSERT_NE(block, std::string::npos) << figures;
  EXPECT_NE(figures.find("| 32 | ", block), std::string::npos) << figures;
  fs::remove_all(dir.parent_path());
}

// The pillars axis: tiled and clustered on many-lights:N:pillars (64 lights
// and up), kept apart from the field's points, with tiled on the field at the
// same counts (--only pillars keeps those; untimed: figures only).
TEST(BenchCli, PillarsAxisRendersTheDiscontinuousScene) {
  const fs::path dir = freshDir("pillars");
  const RunResult r = run("bench --quick --figures-only --only pillars --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "results.json"));
  std::map<int, std::map<std::string, nlohmann::json>> pillars, field;  // lights -> method -> row
  for (const auto& p : j.at("points")) {
    const auto axes = p.at("axes").get<std::vector<std::string>>();
    if (p.value("scene_variant", std::string()) == "pillars") {
      EXPECT_EQ(axes, std::vector<std::string>{"pillars"});
      pillars[p.at("lights").get<int>()][p.at("method").get<std::string>()] = p;
    } else {
      EXPECT_NE(std::count(axes.begin(), axes.end(), "lights"), 0) << p.dump();
      field[p.at("lights").get<int>()][p.at("method").get<std::string>()] = p;
    }
  }
  ASSERT_EQ(pillars.size(), 3u) << "64, 256 and 1,024 lights";
  for (const auto& [n, methods] : pillars) {
    SCOPED_TRACE("lights " + std::to_string(n));
    ASSERT_EQ(methods.size(), 2u);
    ASSERT_TRUE(field[n].count("tiled"));
    const double tiled = methods.at("tiled").at("psnr_db").get<double>();
    // A lit image of its own scene (not black, not the field's), and both
    // methods cull only what adds nothing at the same cut-off.
    EXPECT_GT(tiled, 12.0);
    EXPECT_NEAR(methods.at("clustered").at("psnr_db").get<double>(), tiled, 0.5);
    EXPECT_NE(field[n].at("tiled").at("psnr_db").get<double>(), tiled);
  }
  const std::string csv = slurp(dir / "results.csv");
  EXPECT_NE(csv.find(",pillars,"), std::string::npos) << csv;
  const std::string figures = slurp(dir / "figures.md");
  EXPECT_NE(figures.find("| 1,024 pillars |"), std::string::npos) << figures;
  fs::remove_all(dir.parent_path());
}

TEST(BenchCli, UnwritableOutputFolderFails) {
  const RunResult r = run("bench --smoke --out /proc/rgraph-no-such-dir/x");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("error"), std::string::npos) << r.out;
}

TEST(BenchCli, OutIsRequired) {
  const RunResult r = run("bench --quick");
  EXPECT_NE(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("--out"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------- charts

using namespace rgraph::cli::chart;

TEST(BenchChart, ParetoFrontKeepsOnlyUndominatedPoints) {
  // x: PSNR (higher better), y: ms (lower better).
  const std::vector<Point> pts = {{30, 10, ""}, {40, 20, ""}, {35, 30, ""}, {50, 100, ""}, {50, 120, ""}, {20, 10, ""}};
  const std::vector<size_t> front = paretoFront(pts, /*maximizeX=*/true, /*maximizeY=*/false);
  EXPECT_EQ(front, (std::vector<size_t>{0, 1, 3}));  // sorted by x; (35,30), (50,120), (20,10) are dominated
}

// A small chart: title, axis labels, one series in the palette's first
// colour (0, 114, 178), a point label, a legend.
Chart smallChart() {
  Chart c;
  c.title = "Title";
  c.xLabel = "lights";
  c.yLabel = "ms";
  c.logX = c.logY = true;
  c.width = 480;
  c.height = 300;
  Series& s = c.seriesNamed("a & b");
  s.line = true;
  s.points = {{1, 2, ""}, {10, 20, "p<1>"}, {100, 200, ""}};
  return c;
}

struct Pixels {
  std::vector<uint8_t> rgba;
  int width = 0;
  const uint8_t* at(int x, int y) const { return &rgba[(static_cast<size_t>(y) * width + x) * 4]; }
  // Pixels in [x0, x1) x [y0, y1) that pass `test`.
  template <typename F>
  size_t count(int x0, int y0, int x1, int y1, F test) const {
    size_t n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += test(at(x, y)) ? 1 : 0;
    return n;
  }
};
bool dark(const uint8_t* p) { return p[0] < 100 && p[1] < 100 && p[2] < 100; }
bool grey(const uint8_t* p) { return p[0] == p[1] && p[1] == p[2] && p[0] > 40 && p[0] < 215; }
bool blue(const uint8_t* p) { return p[2] > p[0] + 60; }

// The PNG's pixels: the axis label, the title and the legend are drawn as
// antialiased text (grey edge pixels, not only black), the series in its
// colour inside the plot area; without the x label its band stays blank.
TEST(BenchChart, ImageHasAntialiasedTextAndTheSeries) {
  const Chart c = smallChart();
  const Pixels img{toRgba(c), c.width};
  ASSERT_EQ(img.rgba.size(), 480u * 300u * 4u);
  EXPECT_EQ(img.count(0, 0, 2, 2, [](const uint8_t* p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }), 4u);
  const int labelBand[4] = {120, c.height - 30, 300, c.height - 10};  // under the plot, centred
  EXPECT_GT(img.count(labelBand[0], labelBand[1], labelBand[2], labelBand[3], dark), 15u);
  EXPECT_GT(img.count(0, 0, c.width, c.height, grey), 200u);  // antialiased edges of glyphs
  EXPECT_GT(img.count(180, 10, 300, 30, dark), 15u);          // the title
  EXPECT_GT(img.count(80, 40, 380, 240, blue), 150u);         // the line and markers in the plot area
  EXPECT_GT(img.count(380, 40, 480, 100, dark), 15u);         // the legend's name
  Chart bare = c;
  bare.xLabel.clear();
  bare.logX = false;  // no " (log)" either
  const Pixels none{toRgba(bare), bare.width};
  EXPECT_EQ(none.count(labelBand[0], labelBand[1], labelBand[2], labelBand[3], dark), 0u);
}

// The SVG is the same drawing: one glyph per visible character of its text
// (cairo writes glyphs, not <text>), the series' stroke colour, the size.
TEST(BenchChart, SvgHasTheTextAndTheSeries) {
  const Chart c = smallChart();
  const std::string svg = toSvg(c);
  EXPECT_NE(svg.find("width=\"480pt\" height=\"300pt\""), std::string::npos) << svg.substr(0, 300);
  EXPECT_NE(svg.find("rgb(0%,44.705882%,69.803922%)"), std::string::npos);  // (0, 114, 178)
  auto uses = [](const std::string& s) {
    size_t n = 0;
    for (size_t at = s.find("xlink:href=\"#glyph"); at != std::string::npos; at = s.find("xlink:href=\"#glyph", at + 1))
      ++n;
    return n;
  };
  // Title, labels with " (log)", the series name and the point label, without spaces.
  const std::string text = "Title" "lights(log)" "ms(log)" "a&b" "p<1>";
  EXPECT_GE(uses(svg), text.size());
  Chart bare = c;
  bare.title.clear();
  EXPECT_EQ(uses(svg) - uses(toSvg(bare)), 5u);  // the title's glyphs, no more
}

}  // namespace
