// Shadows through the public renderer API (issue 28): cascades follow the
// camera and spot and point maps follow their lights frame by frame without
// rebuilding the pipeline or creating GL objects, and what a moving frame
// draws is exactly what a renderer built for that final state draws.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;

constexpr Extent kSize{160, 90};

class RendererShadows : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

// deferred-pbr-shadows.json with 256^2 maps (the test draws 100 frames of 24 layers).
std::string pipelineText() {
  std::ifstream in(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr-shadows.json");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc = nlohmann::json::parse(text.str());
  for (auto& pass : doc["passes"])
    if (pass["type"] == "shadow_map") pass["params"]["size"] = 256;
  return doc.dump();
}

std::unique_ptr<Renderer> makeRenderer() {
  RendererOptions options;
  options.size = kSize;
  Diagnostics diags;
  auto r = Renderer::fromJson(pipelineText(), "deferred-pbr-shadows.json (256^2 maps)", options, diags);
  EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  return r;
}

size_t differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = a.size() != b.size();
  for (size_t i = 0; i + 3 < std::min(a.size(), b.size()); i += 4)
    n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
  return n;
}

size_t livePassesNamed(const Renderer& r, const std::string& prefix) {
  size_t n = 0;
  for (const PlannedPass& p : r.plan().passes) n += !p.culled && p.name.rfind(prefix, 0) == 0;
  return n;
}

// The must-show: a 100-frame orbit of the camera around scenes/shadows.json
// while its spot and shadowed point lights circle in place (staying in view)
// builds the pipeline once and creates no GL object after the first frame.
TEST_F(RendererShadows, AnOrbitWithMovingShadowedLightsNeverRebuilds) {
  auto scene = RenderScene::load(std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json");
  auto r = makeRenderer();
  r->setScene(scene);
  r->render();
  ASSERT_EQ(r->builds(), 1u);
  // The sun's 4 cascades, 2 spot maps and 3 point cubes, and the info pass.
  EXPECT_EQ(livePassesNamed(*r, "shadows."), 10u);
  const int64_t created = gl::createdObjectsTotal();
  std::vector<PointLight> start;
  for (size_t i = 0; i < scene->pointLightCount(); ++i) start.push_back(scene->pointLight(i));
  const Camera first = r->camera();
  std::vector<uint8_t> previous = r->readOutputRGBA8();
  size_t unchangedFrames = 0;
  for (int frame = 1; frame <= 100; ++frame) {
    Camera c = first;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(3.6f * float(frame)), glm::vec3(0, 1, 0));
    c.position = c.target + glm::vec3(turn * glm::vec4(first.position - first.target, 0.0f));
    r->setCamera(c);
    for (size_t i = 0; i < start.size(); ++i) {
      PointLight l = start[i];
      const float a = 0.2f * float(frame) + float(i);
      l.position += 0.4f * glm::vec3(std::cos(a), 0.0f, std::sin(a));
      if (l.spot) l.direction = glm::normalize(l.direction + 0.2f * glm::vec3(std::sin(a), 0.0f, std::cos(a)));
      scene->setPointLight(i, l);
    }
    r->render();
    std::vector<uint8_t> image = r->readOutputRGBA8();
    unchangedFrames += differing(image, previous) < 50;
    previous = std::move(image);
  }
  EXPECT_EQ(r->builds(), 1u) << "moving lights that stay in view, and a moving camera, re-compiled the pipeline";
  EXPECT_EQ(gl::createdObjectsTotal() - created, 0) << "GL objects created by camera and light moves";
  EXPECT_EQ(unchangedFrames, 0u) << "every frame should move";

  // The maps followed exactly: a fresh renderer of the final state draws the same frame.
  auto fresh = makeRenderer();
  fresh->setScene(RenderScene::fromScene(scene->scene()));
  fresh->setCamera(r->camera());
  fresh->render();
  EXPECT_EQ(differing(fresh->readOutputRGBA8(), previous), 0u);
}

}  // namespace
