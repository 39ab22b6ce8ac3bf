// Depth blit: the G-buffer depth copied into the forward pass's depth buffer
// hides a light marker behind an object and keeps one in front visible. One
// cube, a red light behind it and a green light in front, both projecting
// onto the cube; checked through every shipped pipeline that draws markers.
#include <cstdio>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{128, 128};

Scene markerScene(bool withCube) {
  Scene s;
  s.source = "test:markers";
  const int cube = addMesh(s, makeCube(1.0f));
  const int mat = addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.7f);
  // The control scene moves the cube out of the view (a scene needs geometry).
  addDraw(s, cube, mat, withCube ? glm::mat4(1.0f) : translate({40.0f, 0.0f, 0.0f}), "cube");
  s.pointLights.push_back(pointLight({0.3f, 0.2f, -2.5f}, {1.0f, 0.0f, 0.0f}));    // behind the cube
  s.pointLights.push_back(pointLight({-0.3f, -0.2f, 2.5f}, {0.0f, 1.0f, 0.0f}));  // in front of it
  s.camera.position = glm::vec3(0.0f, 0.0f, 6.0f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = 50.0f;
  s.hasCamera = true;
  return s;
}

// A marker's pixel: its channel bright, the others dark (markers are unlit,
// in the light's colour; tone curves keep a pure primary pure).
bool markerLike(glm::ivec3 c, int channel) {
  for (int i = 0; i < 3; ++i)
    if (i == channel ? c[i] < 180 : c[i] > 30) return false;
  return true;
}

class DepthBlit : public RenderTest, public ::testing::WithParamInterface<const char*> {};

}  // namespace

TEST_P(DepthBlit, MarkerBehindAnObjectIsHiddenAndOneInFrontIsVisible) {
  const std::string pipeline = GetParam();
  const Scene scene = markerScene(true);
  const Scene control = markerScene(false);
  // Both markers project onto the cube's front face.
  const auto red = project(scene.camera, kSize, scene.pointLights[0].position);
  const auto green = project(scene.camera, kSize, scene.pointLights[1].position);
  ASSERT_TRUE(red && green);
  const Ray toRed = pixelRay(scene.camera, kSize, red->px(), red->prow());
  const auto cubeHit = hitBox(toRed, glm::dvec3(-1.0), glm::dvec3(1.0));
  ASSERT_TRUE(cubeHit.has_value());
  ASSERT_LT(*cubeHit + 0.5, glm::length(glm::dvec3(scene.pointLights[0].position) - toRed.origin))
      << "the red light must lie behind the cube along its pixel's ray";

  const PipelineConfig cfg = loadPipeline(repoPath("pipelines/" + pipeline));
  const Image img = render(cfg, scene, kSize, *shaders);
  const Image ctl = render(cfg, control, kSize, *shaders);
  const glm::ivec3 redPx = img.rgb(red->px(), red->prow()), greenPx = img.rgb(green->px(), green->prow());
  std::printf("[ measure  ] %s: pixel at the hidden red marker %s (without the cube %s), at the green marker %s\n",
              pipeline.c_str(), pixelText(redPx).c_str(), pixelText(ctl.rgb(red->px(), red->prow())).c_str(),
              pixelText(greenPx).c_str());
  // Control: with the cube out of the way the red marker shows at that pixel.
  EXPECT_TRUE(markerLike(ctl.rgb(red->px(), red->prow()), 0))
      << "control: the red marker should be visible without the cube " << saveImage(ctl, "markers-control");
  EXPECT_FALSE(markerLike(redPx, 0)) << "the red marker behind the cube shows through: "
                                     << pixelText(redPx) << " " << saveImage(img, "markers-" + pipeline);
  EXPECT_TRUE(markerLike(greenPx, 1)) << "the green marker in front of the cube is hidden: " << pixelText(greenPx)
                                      << " " << saveImage(img, "markers-" + pipeline);
  // The cube itself is drawn around the hidden marker (lit by the green light).
  EXPECT_GT(redPx.g, redPx.r);
}

INSTANTIATE_TEST_SUITE_P(ShippedPipelines, DepthBlit,
                         ::testing::Values("default.json", "deferred-blinn-phong.json", "deferred-light-volumes.json",
                                           "deferred-pbr.json", "deferred-fp32.json", "deferred-compact.json",
                                           "forward.json"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string n = info.param;
                           n = n.substr(0, n.find('.'));
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });
