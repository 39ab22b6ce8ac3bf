// Runs `rgraph plan --json` / `validate --json` and checks the parsed output.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

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
  EXPECT_EQ(plan.at("memory").at("peak_live_bytes"), 2 * texture) << "two live at each pass of the chain";
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

TEST(CliPlanJson, HistoryResourcesAreLinkedKeptAndOwnTheirTextures) {
  RunResult r = run("plan --json --width 640 --height 360 " + kConfigs + "history.json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  auto plan = nlohmann::json::parse(r.out);
  const auto& resources = plan.at("resources");
  for (const auto& [history, source] : {std::pair{"echo_prev", "echo"}, std::pair{"trail_prev", "trail"}}) {
    const auto* h = findByName(resources, history);
    const auto* s = findByName(resources, source);
    ASSERT_TRUE(h && s) << history;
    EXPECT_EQ(h->at("history_of"), source);
    EXPECT_TRUE(s->at("history_of").is_null());
    EXPECT_TRUE(h->at("kept_across_frames").get<bool>()) << history;
    EXPECT_TRUE(s->at("kept_across_frames").get<bool>()) << source;
    // The whole frame (4 passes), each in a physical texture of its own.
    for (const auto* e : {h, s}) {
      EXPECT_EQ(e->at("first_order"), 0) << e->at("name");
      EXPECT_EQ(e->at("last_order"), 3) << e->at("name");
      const auto& phys = plan.at("physical").at(e->at("physical").get<size_t>());
      EXPECT_EQ(phys.at("resources").size(), 1u) << e->at("name");
    }
  }
  const auto* scene = findByName(resources, "scene");
  ASSERT_NE(scene, nullptr);
  EXPECT_FALSE(scene->at("kept_across_frames").get<bool>());
  EXPECT_TRUE(scene->at("history_of").is_null());
  // 'trail' feeds only the next frame: it runs, and says why.
  const auto* trail = findByName(plan.at("passes"), "trail");
  ASSERT_NE(trail, nullptr);
  EXPECT_FALSE(trail->at("culled").get<bool>());
  EXPECT_EQ(trail->at("reason"), "kept: it feeds 'trail', whose history 'trail_prev' is read in the next frame");
  const uint64_t texture = 640ull * 360 * 8;
  EXPECT_EQ(plan.at("memory").at("allocated_bytes"), 5 * texture) << "scene, and the two pairs unaliased";
}

TEST(CliValidateJson, ValidConfigPrintsEmptyArray) {
  RunResult r = run("validate --json " + kPipelines + "examples/post-chain.json");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_EQ(nlohmann::json::parse(r.out), nlohmann::json::array());
}

}  // namespace
