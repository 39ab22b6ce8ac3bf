// The pass-check corpus: tests/configs/invalid/checks/NAME.json, each refused
// by one pass type's check hook (rgraph/pass_check.h), with its expected first
// diagnostic in NAME.expected (as `rgraph validate` prints it, run in that
// folder). `rgraph render` must refuse each with the same message and exit 1
// before any GL work (render refuses what validate refuses).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"

namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(RGRAPH_SOURCE_DIR) + "/tests/configs/invalid/checks";

struct CliRun {
  int exit = -1;
  std::string out;  // stdout + stderr
};

// Runs the CLI in the corpus folder (messages then name the bare file), with
// a shader-check cache of its own so that no user cache is read or written.
CliRun run(const std::string& args) {
  const std::string cache = (fs::temp_directory_path() / "rgraph-pass-checks-test-cache").string();
  const std::string cmd = "cd '" + kDir + "' && RGRAPH_CACHE_DIR='" + cache + "' " + RGRAPH_CLI + " " + args + " 2>&1";
  const rgraph::testsupport::CommandResult c = rgraph::testsupport::runCommand(cmd);
  CliRun r;
  r.exit = c.exitCode;
  r.out = c.out;
  return r;
}

std::string firstError(const std::string& out) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.find(": error: ") != std::string::npos) return line;
  return {};
}

std::vector<std::string> corpus() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(kDir, ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class PassCheckCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(PassCheckCorpus, ValidateGivesTheExpectedLocatedError) {
  const std::string name = GetParam();
  std::ifstream in(kDir + "/" + name + ".expected");
  ASSERT_TRUE(in) << "missing " << name << ".expected";
  std::string expected;
  std::getline(in, expected);
  const CliRun r = run("validate " + name + ".json");
  EXPECT_EQ(r.exit, 1) << r.out;
  EXPECT_EQ(firstError(r.out), expected) << r.out;

  // The first error is a pass check (not the graph's nor the shaders'), with a JSON path.
  const CliRun j = run("validate --json " + name + ".json");
  const nlohmann::json diags = nlohmann::json::parse(j.out, nullptr, false);
  ASSERT_TRUE(diags.is_array()) << j.out;
  const nlohmann::json* first = nullptr;
  for (const auto& d : diags)
    if (d["severity"] == "error" && !first) first = &d;
  ASSERT_NE(first, nullptr) << j.out;
  EXPECT_EQ((*first)["code"], "pass_check") << j.out;
  EXPECT_GT((*first)["line"].get<int>(), 0);
  EXPECT_GT((*first)["column"].get<int>(), 0);
  EXPECT_EQ((*first)["path"].get<std::string>().rfind("/passes/", 0), 0u) << j.out;
}

TEST_P(PassCheckCorpus, RenderRefusesWithValidatesMessage) {
  const std::string name = GetParam();
  const std::string size = " --width 320 --height 180";
  const CliRun v = run("validate " + name + ".json" + size);
  const std::string out = (fs::temp_directory_path() / ("rgraph-pass-checks-" + name + ".png")).string();
  std::error_code ec;
  fs::remove(out, ec);
  const CliRun r = run("render " + name + ".json" + size + " --out '" + out + "'");
  EXPECT_EQ(r.exit, 1) << r.out;
  ASSERT_FALSE(firstError(v.out).empty()) << v.out;
  EXPECT_EQ(firstError(r.out), firstError(v.out)) << r.out;
  EXPECT_FALSE(fs::exists(out)) << "render wrote an image for a config validate refuses";
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Checks, PassCheckCorpus, ::testing::ValuesIn(corpus()), testName);

TEST(PassCheckCorpusFiles, EveryMovedCheckHasAConfig) {
  // One config per check moved out of setup() (13 when they moved): none lost.
  EXPECT_GE(corpus().size(), 13u);
}

}  // namespace
