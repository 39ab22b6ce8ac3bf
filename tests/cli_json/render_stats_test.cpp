// `rgraph render --stats`: which clock timed the passes and over how many
// frames their medians are (issue 26: GPU timer query results arrive frames
// later; each frame counts once, the last ones after the run).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_command.h"

namespace {

namespace fs = std::filesystem;

TEST(CliRenderStats, PassTimesSayTheirClockAndHowManyFramesTheyAreOf) {
  const fs::path dir = fs::temp_directory_path() / ("rgraph-stats-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string stats = (dir / "s.json").string();
  const auto r = rgraph::testsupport::runCommand("RGRAPH_CACHE_DIR=" + dir.string() + " " + std::string(RGRAPH_CLI) +
                                                 " render " + RGRAPH_SOURCE_DIR +
                                                 "/pipelines/default.json --width 64 --height 48 --frames 4 --out " +
                                                 (dir / "a.png").string() + " --stats " + stats + " 2>&1");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  std::ifstream in(stats);
  const nlohmann::json s = nlohmann::json::parse(in);
  fs::remove_all(dir);
  EXPECT_EQ(s.at("frames"), 4);
  const std::string clock = s.at("pass_clock");
  ASSERT_TRUE(clock == "cpu_glfinish" || clock == "gl_time_elapsed") << clock;
  // The CPU clock times every frame; queries at least the last (waited for after the run).
  if (clock == "cpu_glfinish")
    EXPECT_EQ(s.at("timed_frames"), 4);
  else
    EXPECT_GE(s.at("timed_frames").get<int>(), 1);
  ASSERT_FALSE(s.at("passes").empty());
  double total = 0.0;
  for (const auto& p : s.at("passes")) {
    EXPECT_GE(p.at("ms").get<double>(), 0.0) << p.dump();
    total += p.at("ms").get<double>();
  }
  EXPECT_GT(total, 0.0);
  EXPECT_LE(total, s.at("frame_ms_max").get<double>()) << "the passes' medians add up to more than the longest frame";
}

}  // namespace
