// Every shipped pipeline (pipelines/*.json) under every hazard mode on the
// default procedural scene: no finding (issue 31). Small on purpose (32x32,
// 2 frames: history compared once); `rgraph check-hazards` runs larger ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "rgraph/hazard_check.h"
#include "test_support.h"

namespace {

using namespace rgraph;

std::vector<std::string> shippedPipelines() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + "/pipelines"))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class HazardShipped : public ::testing::TestWithParam<std::string> {};

TEST_P(HazardShipped, NoFindingInAnyMode) {
  testsupport::sharedGlContext();
  HazardCheckOptions o;
  o.size = {32, 32};
  o.frames = 2;
  o.renderer.runChecks = false;  // validate's own tests check them; here only what runs
  const HazardReport r = checkHazards(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + GetParam() + ".json", o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.hazardFree()) << r.describe();
  ASSERT_EQ(r.runs.size(), 8u);
  for (const HazardModeRun& run : r.runs) EXPECT_GT(run.comparedPixels, 0u) << run.mode;
}

INSTANTIATE_TEST_SUITE_P(Pipelines, HazardShipped, ::testing::ValuesIn(shippedPipelines()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

}  // namespace
