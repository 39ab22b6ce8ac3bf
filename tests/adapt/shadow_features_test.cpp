// The shadow facts of SceneFeatures: which lights get a shadow map, in what
// order, and why each other light gets none.
#include <gtest/gtest.h>

#include "rgraph/pass.h"
#include "rgraph/scene.h"
#include "support/cube_scene.h"

namespace rgraph {
namespace {

using Kind = SceneFeatures::ShadowLight::Kind;
using ShadowLight = SceneFeatures::ShadowLight;
using UnshadowedLight = SceneFeatures::UnshadowedLight;

// A 20 x 20 floor (y = 0, x and z in -10..10) that casts, seen from (0, 5, 10)
// looking at the origin (fov 45, near 0.1, far 100).
Scene floorScene() {
  Scene s = testsupport::singleMeshScene(makeCube(0.5f));
  s.primitives[0].bounds.min = {-10.0f, -0.1f, -10.0f};
  s.primitives[0].bounds.max = {10.0f, 0.0f, 10.0f};
  testsupport::lookAtOrigin(s, {0.0f, 5.0f, 10.0f});
  return s;
}

PointLight spotAt(glm::vec3 position, float radius) {
  PointLight l;
  l.spot = true;
  l.position = position;
  l.direction = {0.0f, -1.0f, 0.0f};
  l.radius = radius;
  return l;
}

PointLight pointAt(glm::vec3 position, float radius, bool casts = true) {
  PointLight l;
  l.position = position;
  l.radius = radius;
  l.castShadows = casts;
  return l;
}

TEST(ShadowFeatures, FirstCastingSunIsShadowedOtherSunsAreNotShaded) {
  Scene s = floorScene();
  s.directionalLights.resize(3);  // each casts by default
  s.directionalLights[2].castShadows = false;
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_TRUE(f.shadowCasters);
  EXPECT_EQ(f.shadowLights, (std::vector<ShadowLight>{{Kind::directional, 0}}));
  EXPECT_EQ(f.unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::directional, 1}, "not shaded"},
                                                              {{Kind::directional, 2}, "not shaded"}}));
}

TEST(ShadowFeatures, ASunAfterANonCastingFirstIsStillNotShaded) {
  Scene s = floorScene();
  s.directionalLights.resize(2);
  s.directionalLights[0].castShadows = false;
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_TRUE(f.shadowLights.empty());
  EXPECT_EQ(f.unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::directional, 0}, "does not cast"},
                                                              {{Kind::directional, 1}, "not shaded"}}));
}

TEST(ShadowFeatures, PointLightsCastOnlyWhenAskedSpotsByDefault) {
  Scene s = floorScene();
  PointLight plain;  // castShadows unset: a point light does not cast
  plain.position = {0.0f, 1.0f, 0.0f};
  s.pointLights.push_back(plain);
  s.pointLights.push_back(spotAt({0.0f, 3.0f, 0.0f}, 5.0f));  // unset: a spot casts
  PointLight quietSpot = spotAt({1.0f, 3.0f, 0.0f}, 5.0f);
  quietSpot.castShadows = false;
  s.pointLights.push_back(quietSpot);
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_EQ(f.shadowLights, (std::vector<ShadowLight>{{Kind::spot, 1}}));
  EXPECT_EQ(f.unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::point, 0}, "does not cast"},
                                                              {{Kind::spot, 2}, "does not cast"}}));
}

TEST(ShadowFeatures, LightsWhoseReachMissesTheViewAreOutsideIt) {
  Scene s = floorScene();
  s.pointLights.push_back(pointAt({0.0f, 1.0f, -40.0f}, 2.0f));  // far behind the floor, but in the frustum
  s.pointLights.push_back(pointAt({0.0f, 5.0f, 30.0f}, 2.0f));   // behind the camera
  s.pointLights.push_back(pointAt({60.0f, 1.0f, 0.0f}, 5.0f));   // far to the right
  s.pointLights.push_back(pointAt({0.0f, 1.0f, -200.0f}, 2.0f)); // beyond the far plane (100)
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_EQ(f.shadowLights, (std::vector<ShadowLight>{{Kind::point, 0}}));
  EXPECT_EQ(f.unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::point, 1}, "outside the view"},
                                                              {{Kind::point, 2}, "outside the view"},
                                                              {{Kind::point, 3}, "outside the view"}}));
}

TEST(ShadowFeatures, ALightBehindTheCameraWhoseReachCoversTheCameraIsKeptFirst) {
  Scene s = floorScene();
  s.pointLights.push_back(pointAt({0.0f, 1.0f, 0.0f}, 1.0f));    // in view, 9.7 units away from its sphere
  s.pointLights.push_back(pointAt({0.0f, 5.0f, 13.0f}, 4.0f));   // 3 behind the camera, reach 4: covers it
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_EQ(f.shadowLights, (std::vector<ShadowLight>{{Kind::point, 1}, {Kind::point, 0}}));
  EXPECT_TRUE(f.unshadowedLights.empty());
}

TEST(ShadowFeatures, OrderedByDistanceToTheReachTiesInSceneOrder) {
  Scene s = floorScene();
  s.pointLights.push_back(pointAt({0.0f, 1.0f, -8.0f}, 1.0f));  // farthest
  s.pointLights.push_back(spotAt({3.0f, 1.0f, 0.0f}, 1.0f));    // these two at the same distance
  s.pointLights.push_back(pointAt({-3.0f, 1.0f, 0.0f}, 1.0f));
  s.pointLights.push_back(pointAt({0.0f, 2.0f, 6.0f}, 1.0f));   // nearest
  s.directionalLights.resize(1);
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_EQ(f.shadowLights, (std::vector<ShadowLight>{{Kind::directional, 0},
                                                      {Kind::point, 3},
                                                      {Kind::spot, 1},
                                                      {Kind::point, 2},
                                                      {Kind::point, 0}}));
}

TEST(ShadowFeatures, ReachIsCappedAtTheFarthestCornerOfTheScene) {
  Scene s = floorScene();
  s.camera.position = {0.0f, 5.0f, 30.0f};
  s.pointLights.push_back(pointAt({0.0f, 2.0f, 20.0f}, 1.0f));  // 10.4 from the camera: 9.4 from its sphere
  // Reach 1000 would cover the camera (distance 0, first); capped at the
  // floor's farthest corner (31.6 away) its sphere is 18.6 from the camera.
  s.pointLights.push_back(pointAt({0.0f, 1.0f, -20.0f}, 1000.0f));
  EXPECT_EQ(sceneFeatures(s).shadowLights, (std::vector<ShadowLight>{{Kind::point, 0}, {Kind::point, 1}}));
  // The cap follows the scene: a floor reaching past the camera (its far
  // corner 80.6 from the light) lets the reach cover the camera again.
  s.primitives[0].bounds.max.z = 60.0f;
  EXPECT_EQ(sceneFeatures(s).shadowLights, (std::vector<ShadowLight>{{Kind::point, 1}, {Kind::point, 0}}));
}

TEST(ShadowFeatures, RadiusZeroUsesTheLightsCutOffDistance) {
  Scene s = floorScene();
  PointLight l = pointAt({0.0f, 5.0f, 16.0f}, 0.0f);  // 6 behind the camera
  l.linear = 0.0f;
  l.quadratic = 0.0f;
  l.constant = 1.0f;  // no falloff: an infinite cut-off, capped by the scene
  s.pointLights.push_back(l);
  EXPECT_EQ(sceneFeatures(s).shadowLights, (std::vector<ShadowLight>{{Kind::point, 0}}));
  s.pointLights[0].intensity = 0.001f;  // never as bright as the threshold: reach 0, behind the camera
  s.pointLights[0].linear = 0.7f;
  EXPECT_EQ(sceneFeatures(s).unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::point, 0}, "outside the view"}}));
}

TEST(ShadowFeatures, TheViewIsTheCameraAndAspectGiven) {
  Scene s = floorScene();
  s.pointLights.push_back(pointAt({12.0f, 1.0f, 0.0f}, 1.0f));  // right of a 16:9 view at this distance
  EXPECT_EQ(sceneFeatures(s).unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::point, 0}, "outside the view"}}));
  // A wide enough view sees it...
  EXPECT_EQ(sceneFeatures(s, s.camera, 4.0f).shadowLights, (std::vector<ShadowLight>{{Kind::point, 0}}));
  // ... and so does a camera turned towards it.
  Camera turned = s.camera;
  turned.target = {12.0f, 0.0f, 0.0f};
  EXPECT_EQ(sceneFeatures(s, turned, 16.0f / 9.0f).shadowLights, (std::vector<ShadowLight>{{Kind::point, 0}}));
}

TEST(ShadowFeatures, NoCasterLeavesEveryLightUnshadowed) {
  Scene s = floorScene();
  s.primitives[0].castShadows = false;
  s.directionalLights.resize(2);
  s.pointLights.push_back(spotAt({0.0f, 3.0f, 0.0f}, 5.0f));
  s.pointLights.push_back(pointAt({0.0f, 1.0f, 0.0f}, 5.0f, false));
  const SceneFeatures f = sceneFeatures(s);
  EXPECT_FALSE(f.shadowCasters);
  EXPECT_TRUE(f.shadowLights.empty());
  const std::string why = "no caster in the scene";
  EXPECT_EQ(f.unshadowedLights, (std::vector<UnshadowedLight>{{{Kind::directional, 0}, why},
                                                              {{Kind::directional, 1}, why},
                                                              {{Kind::spot, 0}, why},
                                                              {{Kind::point, 1}, why}}));
}

TEST(ShadowFeatures, BlendPrimitivesDoNotCastByDefault) {
  Scene s = floorScene();
  s.materials[0].alphaMode = AlphaMode::blend;
  s.directionalLights.resize(1);
  EXPECT_FALSE(sceneFeatures(s).shadowCasters);
  s.primitives[0].castShadows = true;
  EXPECT_TRUE(sceneFeatures(s).shadowCasters);
  EXPECT_EQ(sceneFeatures(s).shadowLights, (std::vector<ShadowLight>{{Kind::directional, 0}}));
}

}  // namespace
}  // namespace rgraph
