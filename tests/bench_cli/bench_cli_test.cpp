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
  EXPECT_TRUE(j.at("machine").contains("renderer"));

  // Charts: SVG and PNG of each.
  for (const char* name : {"frame_ms_vs_lights", "frame_ms_vs_error", "bytes_vs_error"}) {
    const std::string svg = slurp(dir / (std::string(name) + ".svg"));
    EXPECT_EQ(svg.rfind("<svg", 0), 0u) << name;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << name;
    const std::string png = slurp(dir / (std::string(name) + ".png"));
    ASSERT_GT(png.size(), 8u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
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
    ASSERT_EQ(at[n].size(), 7u);
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
      EXPECT_GT(at[n]["tiled_far"].at("psnr_exact_db").get<double>(),
                at[n]["tiled"].at("psnr_exact_db").get<double>() + 1.0);
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

TEST(BenchChart, SvgAndRasterDrawTheSameChart) {
  Chart c;
  c.title = "t";
  c.xLabel = "lights";
  c.yLabel = "ms";
  c.logX = c.logY = true;
  c.width = 320;
  c.height = 200;
  Series s;
  s.name = "a & b";
  s.points = {{1, 2, ""}, {10, 20, "p<1>"}, {100, 200, ""}};
  c.series.push_back(s);
  const std::string svg = toSvg(c);
  EXPECT_NE(svg.find("a &amp; b"), std::string::npos);  // escaped
  EXPECT_NE(svg.find("p&lt;1&gt;"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  const std::vector<uint8_t> rgba = toRgba(c);
  ASSERT_EQ(rgba.size(), 320u * 200u * 4u);
  size_t dark = 0, coloured = 0;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    dark += rgba[i] < 80 && rgba[i + 1] < 80 && rgba[i + 2] < 80;
    coloured += std::abs(int(rgba[i]) - int(rgba[i + 2])) > 60;  // the series' blue
  }
  EXPECT_GT(dark, 500u);      // axes and text
  EXPECT_GT(coloured, 100u);  // the line and its markers
}

}  // namespace
