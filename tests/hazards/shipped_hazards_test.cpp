// Every shipped pipeline (pipelines/*.json) under every hazard mode on the
// default procedural scene: no finding (issue 31). Small on purpose (32x32,
// 2 frames: history compared once); `rgraph check-hazards` runs larger ones.
#include <gtest/gtest.h>

#include <string>

#include "hazards/shipped_pipelines.h"
#include "rgraph/hazard_check.h"
#include "test_support.h"

namespace {

using namespace rgraph;

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

INSTANTIATE_TEST_SUITE_P(Pipelines, HazardShipped, ::testing::ValuesIn(hazardtest::shippedPipelines()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return hazardtest::testName(i.param); });

}  // namespace
