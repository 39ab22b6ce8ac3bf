// `rgraph render --stats` records the context it rendered with (its
// "context" object: GL_VENDOR, GL_RENDERER, GL_VERSION, the EGL platform and
// device), and RGRAPH_EGL_DEVICE=0 renders on device 0 of the enumeration.
// (bench's results.json: BenchCli.SmokeSweepWritesResultsAndCharts.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>

#include "bench_cli/context_json.h"
#include "support/run_command.h"

namespace {
namespace fs = std::filesystem;

struct Rendered {
  int exitCode = -1;
  std::string out;
  nlohmann::json stats;
};

// `rgraph render` of the default pipeline at 32x32 with --stats, `env` in
// front (VAR=VALUE ... or empty).
Rendered renderWithStats(const std::string& env) {
  const fs::path dir = fs::temp_directory_path() / ("rgraph-context-json-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto r = rgraph::testsupport::runCommand(
      "env RGRAPH_CACHE_DIR=" + (dir / "cache").string() + " " + env + " " + RGRAPH_CLI +
      " render --width 32 --height 32 --out " + (dir / "a.png").string() + " --stats " +
      (dir / "stats.json").string() + " 2>&1");
  Rendered out{r.exitCode, r.out, {}};
  std::ifstream f(dir / "stats.json");
  if (f) out.stats = nlohmann::json::parse(f);
  fs::remove_all(dir);
  return out;
}

TEST(RenderStats, RecordTheContextsGlStrings) {
  const rgraph::ContextDevice device = rgraph::test::thisProcessDevice();
  const Rendered r = renderWithStats("");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  ASSERT_TRUE(r.stats.contains("context")) << r.stats.dump(2);
  rgraph::test::expectContextJson(r.stats.at("context"), device);
  EXPECT_FALSE(r.stats.at("context").at("renderer").get<std::string>().empty());
  EXPECT_TRUE(r.stats.contains("frame_ms")) << "the figures it had before are still there";
}

TEST(RenderStats, EglDeviceZeroRendersOnDeviceZero) {
  const Rendered r = renderWithStats("RGRAPH_EGL_DEVICE=0");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json& c = r.stats.at("context");
  EXPECT_EQ(c.at("platform"), "egl-device") << c.dump();
  EXPECT_EQ(c.at("egl_device"), 0) << c.dump();
  EXPECT_TRUE(c.at("egl_device_description").is_string()) << c.dump();
  EXPECT_NE(c.at("version").get<std::string>().find("4.5"), std::string::npos) << c.dump();
}

}  // namespace
