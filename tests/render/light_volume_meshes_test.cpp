// What the light_volumes pass owns since it left core (issue 27): the spot
// volume mesh and the cut-off radii every lighting pass binds lights with.
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "rgraph/error.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/light_volume_meshes.h"
#include "rgraph/scene.h"

using namespace rgraph;
using rgraph::light_volumes::makeSpotVolume;

namespace {

// The spot-light volume: closed (every edge used twice, once each way),
// convex and wound outward, so that front-face culling draws exactly its far
// side; apex at the origin, rings at z = 1 and 2 on the unit circle.
TEST(LightVolumeMeshes, SpotVolumeIsClosedConvexAndOutward) {
  const MeshData m = makeSpotVolume(16);
  std::string why;
  ASSERT_TRUE(m.valid(&why)) << why;
  EXPECT_EQ(m.vertexCount(), 2u * 16u + 2u);
  EXPECT_EQ(m.triangleCount(), 4u * 16u);
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeated";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "edge " << edge.first << "-" << edge.second << " is open";
  }
  // Convex and outward: every vertex lies on or behind every face's plane,
  // and an interior point strictly behind.
  const glm::vec3 inside(0.0f, 0.0f, 1.2f);
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    ASSERT_LT(glm::dot(n, inside - a), -0.05f) << "triangle " << t << " faces inward";
    for (const glm::vec3& p : m.positions) ASSERT_LE(glm::dot(n, p - a), 1e-5f) << "not convex at triangle " << t;
  }
  EXPECT_EQ(m.positions[0], glm::vec3(0.0f));
  EXPECT_EQ(m.bounds.min.z, 0.0f);
  EXPECT_EQ(m.bounds.max.z, 2.0f);
  EXPECT_THROW(makeSpotVolume(2), RuntimeError);
}

// Radii: lightRadius for the threshold, capped at the farthest geometry
// (the scene's bounds seen from the light), 0 for a light with no falloff
// beyond any bounds... and -1 (no cut-off) for a threshold <= 0.
TEST(LightRadii, ThresholdRadiiAreCappedAtTheSceneAndNegativeWithoutCutoff) {
  Scene s;
  s.meshes.push_back(makeCube(1.0f));
  s.materials.push_back(Material{});
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.bounds = s.meshes[0].bounds;
  s.primitives.push_back(p);
  PointLight near, bright;
  near.position = {0.0f, 0.0f, 0.0f};
  near.intensity = 0.05f;  // reaches 5/256 at ~0.76, inside the cube's bounds
  bright.position = {3.0f, 0.0f, 0.0f};
  bright.intensity = 1000.0f;
  s.pointLights = {near, bright};
  const float threshold = 5.0f / 256.0f;
  const std::vector<float> r = lighting::cutoffRadii(s, threshold);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0], lightRadius(near, threshold));  // inside the cap
  const float cap = glm::length(bright.position - s.bounds().center()) + s.bounds().radius();
  ASSERT_GT(lightRadius(bright, threshold), cap);
  EXPECT_EQ(r[1], cap);
  for (float none : lighting::cutoffRadii(s, 0.0f)) EXPECT_EQ(none, -1.0f);
}

}  // namespace
