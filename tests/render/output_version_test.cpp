// "output" naming an intermediate version renders exactly that version.
// The default pipeline with "output": "hdr_lit" (ambient + light volumes, the
// light boxes not drawn yet) must give the very pixels of the same pipeline
// without the light-box pass, and the light-box pass must be culled: before,
// the final version (with the boxes) was shown.
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "support/test_support.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{192, 108};

class OutputVersionImage : public RenderTest {};

nlohmann::json defaultPipeline() {
  std::ifstream in(repoPath("pipelines/default.json"));
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

PipelineConfig build(const nlohmann::json& j, const std::string& name) {
  return testsupport::buildPipelineOrThrow(j.dump(2), name);
}

const PlannedPass* plannedPass(const Plan& plan, const std::string& name) {
  for (const auto& p : plan.passes)
    if (p.name == name) return &p;
  return nullptr;
}

TEST_F(OutputVersionImage, IntermediateVersionRendersLikeTheGraphWithoutTheLaterPass) {
  const Scene scene = makeLearnOpenGLScene();
  nlohmann::json intermediate = defaultPipeline();
  intermediate["output"] = "hdr_lit";
  // The same graph without the pass that writes the later version (and the
  // tone mapping that reads that version).
  nlohmann::json without = intermediate;
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& p : without["passes"])
    if (p["name"] != "light_boxes" && p["name"] != "tonemap") kept.push_back(p);
  ASSERT_EQ(kept.size(), without["passes"].size() - 2);
  without["passes"] = kept;
  // And the final version, to show the later pass does draw something.
  nlohmann::json finalVersion = defaultPipeline();
  finalVersion["output"] = "hdr_forward";

  const Image a = render(build(intermediate, "intermediate.json"), scene, kSize, *shaders, [](Executor& e) {
    EXPECT_EQ(e.plan().outputVersion, "hdr_lit");
    const PlannedPass* boxes = plannedPass(e.plan(), "light_boxes");
    ASSERT_NE(boxes, nullptr);
    EXPECT_TRUE(boxes->culled);
    EXPECT_NE(boxes->reason.find("'hdr_forward', a later version of 'hdr' than the output 'hdr_lit'"),
              std::string::npos)
        << boxes->reason;
  });
  const Image b = render(build(without, "without.json"), scene, kSize, *shaders);
  const Image c = render(build(finalVersion, "final.json"), scene, kSize, *shaders);

  EXPECT_GT(coverage(a, {0, 0, 0}), 0.2) << saveImage(a, "output-version-intermediate");
  expectLightsShow(a, build(intermediate, "intermediate.json"), scene, *shaders, 0.05, "output-version-intermediate");
  const ImageDiff same = compareImages(a, b, 0);
  EXPECT_EQ(same.maxDiff, 0) << same.describe() << "; " << saveImage(a, "output-version-intermediate");
  EXPECT_EQ(same.over, 0u) << same.describe();
  const ImageDiff boxes = compareImages(a, c, 0);
  std::printf("[ measure  ] output hdr_lit vs hdr_forward (light boxes): %s\n", boxes.describe().c_str());
  EXPECT_GT(boxes.over, 20u) << boxes.describe() << "; " << saveImage(c, "output-version-final");
}

}  // namespace
