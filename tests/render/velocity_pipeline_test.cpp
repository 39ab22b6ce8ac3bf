// Motion vectors through a whole pipeline: the "velocity" output of the
// geometry pass (pipelines/gbuffer-velocity.json) and of forward_lit
// (pipelines/forward-velocity.json) rendered by an Executor, which
// passes the frame number and the previous view-projection to the GPU scene.
// Checked against the CPU motion of the world point each pixel centre sees.
#include <algorithm>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/gl/executor.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"
#include "support/cube_scene.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{96, 64};
constexpr float kTolUv = 1e-3f;  // 1/10 of a pixel here; see tests/gl/motion_vectors_test.cpp

Scene spinningCube() {
  Scene s = testsupport::singleMeshScene(makeCube(0.5f));
  Primitive& p = s.primitives[0];
  p.spin.axis = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f));
  p.spin.degreesPerSecond = 180.0f;  // 3 degrees a frame
  s.directionalLights.push_back(DirectionalLight{});
  testsupport::lookAtOrigin(s, {0.8f, 1.0f, 2.6f});
  return s;
}

glm::dvec2 uvOf(const Camera& cam, glm::dvec3 world) {
  const glm::dmat4 vp = glm::dmat4(cam.projection(float(kSize.width) / float(kSize.height)) * cam.view());
  const glm::dvec4 c = vp * glm::dvec4(world, 1.0);
  return glm::dvec2(c) / c.w * 0.5 + 0.5;
}

struct Compared {
  size_t pixels = 0;
  double maxErr = 0, maxSpeed = 0;
};

// Every pixel whose centre ray meets the cube (away from its edges): the
// velocity read back against uv_now - uv_prev of the point it sees.
Compared compare(const std::vector<float>& v, const Camera& now, const Camera& before, const glm::mat4& modelNow,
                 const glm::mat4& modelBefore) {
  const glm::dmat4 toLocal = glm::inverse(glm::dmat4(modelNow));
  Compared c;
  for (int row = 0; row < int(kSize.height); ++row)
    for (int x = 0; x < int(kSize.width); ++x) {
      const Ray world = pixelRay(now, kSize, x, row);
      Ray local;
      local.origin = glm::dvec3(toLocal * glm::dvec4(world.origin, 1.0));
      local.dir = glm::normalize(glm::dvec3(toLocal * glm::dvec4(world.dir, 0.0)));
      const auto t = hitBox(local, glm::dvec3(-0.5), glm::dvec3(0.5));
      if (!t) continue;
      const glm::dvec3 p = local.origin + *t * local.dir;
      int atEdge = 0;
      for (int k = 0; k < 3; ++k) atEdge += std::abs(p[k]) > 0.48;
      if (atEdge > 1) continue;
      const glm::dvec2 expected = uvOf(now, glm::dvec3(glm::dmat4(modelNow) * glm::dvec4(p, 1.0))) -
                                  uvOf(before, glm::dvec3(glm::dmat4(modelBefore) * glm::dvec4(p, 1.0)));
      // Rows top-down in the read-back, v up in UV.
      const size_t i = (size_t(row) * kSize.width + size_t(x)) * 4;
      const glm::dvec2 got(v[i], v[i + 1]);
      c.maxErr = std::max(c.maxErr, glm::length(got - expected));
      c.maxSpeed = std::max(c.maxSpeed, glm::length(expected));
      ++c.pixels;
    }
  std::printf("[ measure  ] %zu pixels: velocity error max %.2e UV, largest motion %.4f UV\n", c.pixels, c.maxErr,
              c.maxSpeed);
  return c;
}

size_t moving(const std::vector<float>& v) {
  size_t n = 0;
  for (size_t i = 0; i < v.size(); i += 4) n += v[i] != 0.0f || v[i + 1] != 0.0f;
  return n;
}

}  // namespace

class VelocityPipeline : public RenderTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(VelocityPipeline, FollowsCameraSpinAndCuts) {
  const PipelineConfig cfg = loadPipeline(testPipeline(GetParam()));
  const Scene scene = spinningCube();
  Executor exec(cfg, processRegistry(), *shaders, &scene);
  exec.resize(kSize);
  const Primitive& cube = scene.primitives[0];

  // First frame: nothing before it, no motion.
  const uint64_t f0 = exec.frameIndex();
  exec.renderFrame();
  EXPECT_EQ(moving(exec.readTextureRGBA32F("gVelocity")), 0u);

  // Second frame: the camera moves and the cube turns 3 degrees.
  Camera moved = scene.camera;
  moved.position += glm::vec3(-0.1f, 0.05f, 0.15f);
  exec.setCamera(moved);
  const uint64_t f1 = exec.frameIndex();
  ASSERT_EQ(f1, f0 + 1);
  exec.renderFrame();
  std::vector<float> v = exec.readTextureRGBA32F("gVelocity");
  Compared c = compare(v, moved, scene.camera, cube.transformAt(f1 / 60.0), cube.transformAt(f0 / 60.0));
  EXPECT_GT(c.pixels, 600u);
  EXPECT_GT(c.maxSpeed, 0.02);
  EXPECT_LT(c.maxErr, kTolUv);

  // Third frame: the camera stays, the cube keeps turning.
  const uint64_t f2 = exec.frameIndex();
  exec.renderFrame();
  v = exec.readTextureRGBA32F("gVelocity");
  c = compare(v, moved, moved, cube.transformAt(f2 / 60.0), cube.transformAt(f1 / 60.0));
  EXPECT_GT(c.pixels, 600u);
  EXPECT_GT(c.maxSpeed, 0.005);
  EXPECT_LT(c.maxErr, kTolUv);

  // A camera cut: no motion at all, the spin included.
  exec.cameraCut();
  exec.renderFrame();
  v = exec.readTextureRGBA32F("gVelocity");
  EXPECT_EQ(moving(v), 0u);
}

INSTANTIATE_TEST_SUITE_P(Pipelines, VelocityPipeline,
                         ::testing::Values("gbuffer-velocity.json", "forward-velocity.json"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param).substr(0, std::string(info.param).find('-'));
                         });
