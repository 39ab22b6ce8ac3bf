// The thin-geometry scene (makeThinScene, loadSceneAny "thin"): the counts,
// sizes and placement its documentation promises, and that it is the same
// every time (the bench's aa figures depend on it).
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "rgraph/scene.h"

using namespace rgraph;

namespace {

int countPrefix(const Scene& s, const std::string& prefix) {
  int n = 0;
  for (const auto& p : s.primitives) n += p.name.rfind(prefix, 0) == 0;
  return n;
}

// Smallest world-space extent of a primitive's bounds.
float thinnest(const Primitive& p) {
  const glm::vec3 e = p.bounds.max - p.bounds.min;
  return std::min({e.x, e.y, e.z});
}

// Width in pixels of `worldSize` at the distance of `point` from the camera,
// at 360 pixels of height.
float pixelsAt(const Camera& c, glm::vec3 point, float worldSize) {
  const float distance = glm::length(point - c.position);
  const float pixel = 2.0f * std::tan(glm::radians(c.fovY) * 0.5f) * distance / 360.0f;
  return worldSize / pixel;
}

}  // namespace

TEST(ThinScene, HasTheFenceWiresAndGridItClaims) {
  const Scene s = makeThinScene();
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.source, "thin");
  EXPECT_EQ(countPrefix(s, "floor"), 1);
  EXPECT_EQ(countPrefix(s, "post"), kThinScenePosts);
  EXPECT_EQ(countPrefix(s, "wire"), kThinSceneWires);
  EXPECT_EQ(countPrefix(s, "bar_"), kThinSceneGridBars);
  EXPECT_EQ(s.primitives.size(), size_t(1 + kThinScenePosts + kThinSceneWires + kThinSceneGridBars));
  EXPECT_EQ(s.directionalLights.size(), 1u);
  EXPECT_EQ(s.pointLights.size(), 4u);
  EXPECT_TRUE(s.hasCamera);
  EXPECT_FALSE(s.hasTextures());  // flat colours: only geometry edges alias

  for (const auto& p : s.primitives) {
    SCOPED_TRACE(p.name);
    const glm::vec3 centre = (p.bounds.min + p.bounds.max) * 0.5f;
    if (p.name.rfind("post", 0) == 0) {
      EXPECT_NEAR(p.bounds.max.x - p.bounds.min.x, 0.03f, 1e-4f);
      EXPECT_NEAR(p.bounds.max.y - p.bounds.min.y, 1.2f, 1e-4f);
      EXPECT_NEAR(p.bounds.min.y, 0.0f, 1e-4f);  // stands on the floor
      EXPECT_LT(pixelsAt(s.camera, centre, p.bounds.max.x - p.bounds.min.x), 3.5f);
    } else if (p.name.rfind("wire", 0) == 0) {
      EXPECT_GT(p.bounds.max.x - p.bounds.min.x, 7.9f);  // spans the fence
      // Sub-pixel: the depth of the box (the tilt about z leaves it as built).
      const float thickness = p.bounds.max.z - p.bounds.min.z;
      EXPECT_NEAR(thickness, 0.008f, 1e-4f);
      EXPECT_LT(pixelsAt(s.camera, centre, thickness), 1.0f);
      // Tilted: a horizontal wire would be as thin in y as its 0.008 height.
      EXPECT_GT(p.bounds.max.y - p.bounds.min.y, 0.07f);
    } else if (p.name.rfind("bar_", 0) == 0) {
      EXPECT_NEAR(thinnest(p), 0.02f, 1e-4f);  // 0.02 high, 0.03 wide
      EXPECT_LE(p.bounds.max.z, -5.98f);
      EXPECT_GE(p.bounds.min.z, -18.02f);
      const glm::vec3 e = p.bounds.max - p.bounds.min;
      const float width = std::min(e.x, e.z);
      EXPECT_NEAR(width, 0.03f, 1e-4f);
      EXPECT_LT(pixelsAt(s.camera, glm::vec3(0.0f, 0.0f, -6.0f), width), 1.2f);  // about a pixel at most
    }
  }
  // The whole scene: the floor's extent, nothing below it, the wires under the posts' tops.
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.min.x, -10.0f, 1e-4f);
  EXPECT_NEAR(b.max.x, 10.0f, 1e-4f);
  EXPECT_NEAR(b.min.z, -20.0f, 1e-4f);
  EXPECT_NEAR(b.max.z, 8.0f, 1e-4f);
  EXPECT_NEAR(b.min.y, 0.0f, 1e-4f);
  EXPECT_NEAR(b.max.y, 1.2f, 1e-4f);
  // Every post and the grid lie in front of the camera and inside its far plane.
  const glm::mat4 vp = s.camera.viewProjection(640.0f / 360.0f);
  for (const auto& p : s.primitives) {
    if (p.name == "floor") continue;
    const glm::vec4 c = vp * glm::vec4((p.bounds.min + p.bounds.max) * 0.5f, 1.0f);
    ASSERT_GT(c.w, 0.0f) << p.name;
    EXPECT_LE(std::abs(c.z / c.w), 1.0f) << p.name;
    EXPECT_LE(std::abs(c.y / c.w), 1.0f) << p.name;
    if (p.name.rfind("post", 0) == 0) EXPECT_LE(std::abs(c.x / c.w), 1.0f) << p.name;  // the whole fence in view
  }
}

TEST(ThinScene, IsDeterministicAndLoadsByName) {
  const Scene a = makeThinScene(), b = loadSceneAny("thin");
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  for (size_t i = 0; i < a.primitives.size(); ++i) {
    EXPECT_EQ(a.primitives[i].name, b.primitives[i].name);
    EXPECT_EQ(a.primitives[i].transform, b.primitives[i].transform) << a.primitives[i].name;
  }
  ASSERT_EQ(a.pointLights.size(), b.pointLights.size());
  for (size_t i = 0; i < a.pointLights.size(); ++i) EXPECT_EQ(a.pointLights[i].position, b.pointLights[i].position);
  EXPECT_EQ(a.camera.position, b.camera.position);
}
