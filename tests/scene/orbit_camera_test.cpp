// orbitCamera (rgraph/scene.h): the camera turned about its up axis through
// its target (`rgraph render --orbit`, the bench's orbit rows).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "rgraph/scene.h"

namespace {
using namespace rgraph;

void expectNear(glm::vec3 a, glm::vec3 b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

TEST(OrbitCamera, TurnsThePositionAboutTheUpAxisThroughTheTarget) {
  Camera c;
  c.position = {1.0f, 2.0f, 6.0f};
  c.target = {1.0f, 0.0f, 1.0f};
  const Camera quarter = orbitCamera(c, 90.0f);
  // (0, 2, 5) from the target, turned +90 degrees about +Y: (5, 2, 0).
  expectNear(quarter.position, {6.0f, 2.0f, 1.0f});
  expectNear(quarter.target, c.target);
  expectNear(quarter.up, c.up);
  EXPECT_EQ(quarter.fovY, c.fovY);
  expectNear(orbitCamera(c, 360.0f).position, c.position);
  expectNear(orbitCamera(orbitCamera(c, 30.0f), -30.0f).position, c.position);
  expectNear(orbitCamera(c, 0.0f).position, c.position);
}

TEST(OrbitCamera, UsesTheCamerasOwnUp) {
  Camera c;
  c.position = {4.0f, 0.0f, 3.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {0.0f, 0.0f, 2.0f};  // Z up, not unit
  const Camera half = orbitCamera(c, 180.0f);
  expectNear(half.position, {-4.0f, 0.0f, 3.0f});
}

}  // namespace
