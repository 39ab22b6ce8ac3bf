// Runs `rgraph plan --json` / `validate --json` and checks the parsed output.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_command.h"

namespace {

using RunResult = rgraph::testsupport::CommandResult;
RunResult run(const std::string& args) {
  return rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " " + args + " 2>/dev/null");
}

const std::string kPipelines = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/";
const std::string kConfigs = std::string(RGRAPH_SOURCE_DIR) + "/tests/cli/configs/";

const nlohmann::json* findByName(const nlohmann::json& array, const std::string& name) {
  for (const auto& e : array)
    if (e.at("name") == name) return &e;
  return nullptr;
}

TEST(CliPlanJson, CulledDebugPassAndOrderedRest) {
  RunResult r = run("plan --json " + kPipelines + "examples/culled-debug.json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  auto plan = nlohmann::json::parse(r.out);
  const auto& passes = plan.at("passes");
  for (const char* culled : {"debug_source", "debug_view"}) {
    const auto* p = findByName(passes, culled);
    ASSERT_NE(p, nullptr) << culled;
    EXPECT_TRUE(p->at("culled").get<bool>()) << culled;
    EXPECT_TRUE(p->at("order").is_null()) << culled;
    EXPECT_FALSE(p->at("reason").get<std::string>().empty()) << culled;
  }
  const auto* gradient = findByName(passes, "gradient");
  const auto* present = findByName(passes, "present");
  ASSERT_TRUE(gradient && present);
  EXPECT_EQ(gradient->at("order"), 0);
  EXPECT_EQ(present->at("order"), 1);
  // The culled chain's resources are unused: no bytes allocated for them.
  const auto* debugView = findByName(plan.at("resources"), "debugView");
  ASSERT_NE(debugView, nullptr);
  EXPECT_TRUE(debugView->at("physical").is_null());
  EXPECT_TRUE(debugView->at("first_pass").is_null());
}

TEST(CliPlanJson, ChainOfPostPassesNeedsTwoPhysicalTextures) {
  RunResult r = run("plan --json --width 640 --height 360 " + kPipelines + "examples/post-chain.json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  auto plan = nlohmann::json::parse(r.out);
  // Five rgba16f transients (scene, post1..post4) share two textures; the
  // imported output is not pooled.
  EXPECT_EQ(plan.at("physical").size(), 2u);
  const uint64_t texture = 640ull * 360 * 8;
  EXPECT_EQ(plan.at("memory").at("naive_bytes"), 5 * texture);
  EXPECT_EQ(plan.at("memory").at("allocated_bytes"), 2 * texture);
  const auto* post1 = findByName(plan.at("resources"), "post1");
  ASSERT_NE(post1, nullptr);
  EXPECT_EQ(post1->at("first_pass"), "invert1");
  EXPECT_EQ(post1->at("last_pass"), "invert2");
}

TEST(CliValidateJson, MisspelledResourceHasLocation) {
  RunResult r = run("validate --json " + kConfigs + "misspelled-resource.json");
  EXPECT_EQ(r.exitCode, 1);
  auto diags = nlohmann::json::parse(r.out);
  ASSERT_FALSE(diags.empty());
  const auto& d = diags.at(0);
  EXPECT_EQ(d.at("severity"), "error");
  EXPECT_EQ(d.at("code"), "unknown_resource");
  EXPECT_EQ(d.at("line"), 9);
  EXPECT_EQ(d.at("column"), 65);
  EXPECT_EQ(d.at("path"), "/passes/1/inputs/src");
  EXPECT_NE(d.at("file").get<std::string>().find("misspelled-resource.json"), std::string::npos);
}

TEST(CliValidateJson, ValidConfigPrintsEmptyArray) {
  RunResult r = run("validate --json " + kPipelines + "examples/post-chain.json");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out), nlohmann::json::array());
}

}  // namespace
