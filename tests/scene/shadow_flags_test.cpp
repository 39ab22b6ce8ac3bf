// Which lights and primitives cast shadows (issue 28): the defaults (a sun
// and a spot light cast, a point light does not; a blended primitive does
// not), the scene-file keys that override them ("shadows" on a light,
// "cast_shadows" and "light_shadows" on a model), glTF's lights, the scene
// queries, and the shadow scenes (learnopengl:shadows, scenes/shadows.json).
#include <gtest/gtest.h>

#include <algorithm>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::TriangleGltf;

namespace {

class ShadowFlags : public scenetest::TempDirTest {
 protected:
  Scene load(const std::string& text) {
    scenetest::writeText(path("scene.json"), text);
    return loadSceneFile(path("scene.json"));
  }
  void expectError(const std::string& text, const std::string& pointer, const std::string& needle) {
    try {
      load(text);
      ADD_FAILURE() << "expected a RuntimeError for: " << text;
    } catch (const RuntimeError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(pointer), std::string::npos) << msg;
      EXPECT_NE(msg.find(needle), std::string::npos) << msg;
    }
  }
  // A glTF triangle with a point, a spot and a directional light on its node.
  std::string gltfWithLights() {
    TriangleGltf g;
    g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    g.doc["extensions"]["KHR_lights_punctual"]["lights"] = nlohmann::json::parse(
        R"([{"type": "point"}, {"type": "spot", "spot": {"outerConeAngle": 0.5}}, {"type": "directional"}])");
    g.doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "children": [1, 2, 3]},
      {"extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"extensions": {"KHR_lights_punctual": {"light": 2}}}])");
    g.writeGltf(path("lights.gltf"));
    return "lights.gltf";
  }
};

size_t castingPointLights(const Scene& s) {
  return size_t(std::count_if(s.pointLights.begin(), s.pointLights.end(), [](const PointLight& l) { return l.castsShadows(); }));
}

}  // namespace

TEST_F(ShadowFlags, LightDefaultsAndTheShadowsKey) {
  const Scene s = load(R"({"lights": [
    {"type": "point", "position": [0, 1, 0]},
    {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0]},
    {"type": "directional", "direction": [0, -1, 0]},
    {"type": "point", "position": [0, 1, 0], "shadows": true},
    {"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "shadows": false},
    {"type": "directional", "direction": [0, -1, 0], "shadows": false}]})");
  ASSERT_EQ(s.pointLights.size(), 4u);
  ASSERT_EQ(s.directionalLights.size(), 2u);
  EXPECT_FALSE(s.pointLights[0].castsShadows());  // a point light: asked for, not assumed
  EXPECT_TRUE(s.pointLights[1].castsShadows());   // a spot light casts
  EXPECT_TRUE(s.directionalLights[0].castShadows);
  EXPECT_TRUE(s.pointLights[2].castsShadows());
  EXPECT_FALSE(s.pointLights[3].castsShadows());
  EXPECT_FALSE(s.directionalLights[1].castShadows);
  EXPECT_TRUE(s.hasShadowCastingLights());
}

TEST_F(ShadowFlags, NoCastingLightWhenEveryLightSaysSo) {
  const Scene s = load(R"({"models": [{"shape": "cube"}], "lights": [
    {"type": "point", "position": [0, 1, 0]},
    {"type": "directional", "direction": [0, -1, 0], "shadows": false}]})");
  EXPECT_FALSE(s.hasShadowCastingLights());
  EXPECT_TRUE(s.hasShadowCasters());
}

TEST_F(ShadowFlags, PrimitivesCastUnlessTheyBlendOrTheSceneSaysNot) {
  const Scene s = load(R"({"models": [
    {"shape": "cube"},
    {"shape": "cube", "material": {"alphaMode": "BLEND", "baseColor": [1, 1, 1, 0.5]}},
    {"shape": "cube", "cast_shadows": false},
    {"shape": "cube", "material": {"alphaMode": "BLEND"}, "cast_shadows": true}]})");
  ASSERT_EQ(s.primitives.size(), 4u);
  EXPECT_TRUE(s.castsShadows(s.primitives[0]));
  EXPECT_FALSE(s.castsShadows(s.primitives[1]));  // glass lets light through
  EXPECT_FALSE(s.castsShadows(s.primitives[2]));
  EXPECT_TRUE(s.castsShadows(s.primitives[3]));
  const Scene none = load(R"({"models": [{"shape": "plane", "cast_shadows": false}]})");
  EXPECT_FALSE(none.hasShadowCasters());
}

TEST_F(ShadowFlags, GltfLightsCastAsTheirTypeSaysAndTheModelCanOverride) {
  const std::string file = gltfWithLights();
  const Scene plain = loadGltf(path(file));
  ASSERT_EQ(plain.pointLights.size(), 2u);
  ASSERT_EQ(plain.directionalLights.size(), 1u);
  const auto spot = std::find_if(plain.pointLights.begin(), plain.pointLights.end(), [](const PointLight& l) { return l.spot; });
  const auto point = std::find_if(plain.pointLights.begin(), plain.pointLights.end(), [](const PointLight& l) { return !l.spot; });
  ASSERT_NE(spot, plain.pointLights.end());
  ASSERT_NE(point, plain.pointLights.end());
  EXPECT_TRUE(spot->castsShadows());
  EXPECT_FALSE(point->castsShadows());
  EXPECT_TRUE(plain.directionalLights[0].castShadows);

  const Scene on = load(R"({"models": [{"file": ")" + file + R"(", "light_shadows": true}]})");
  EXPECT_EQ(castingPointLights(on), 2u);
  const Scene off = load(R"({"models": [{"file": ")" + file + R"(", "light_shadows": false, "cast_shadows": false}]})");
  EXPECT_EQ(castingPointLights(off), 0u);
  EXPECT_FALSE(off.directionalLights[0].castShadows);
  EXPECT_FALSE(off.hasShadowCasters());
}

TEST_F(ShadowFlags, BadValuesNameTheirPointer) {
  expectError(R"({"lights": [{"type": "point", "position": [0, 0, 0], "shadows": "yes"}]})", "/lights/0/shadows",
              "expected true or false, got string");
  expectError(R"({"lights": [{"type": "directional", "direction": [0, -1, 0], "shadows": 1}]})", "/lights/0/shadows",
              "expected true or false, got number");
  expectError(R"({"models": [{"shape": "cube", "cast_shadows": null}]})", "/models/0/cast_shadows",
              "expected true or false, got null");
  expectError(R"({"models": [{"shape": "cube", "light_shadows": true}]})", "/models/0/light_shadows",
              "a shape brings no lights");
}

TEST(ShadowScenes, LearnOpenGLShadowsIsTheOverviewOnAFloorUnderASun) {
  const Scene overview = loadSceneAny("learnopengl:overview");
  const Scene s = loadSceneAny("learnopengl:shadows");
  EXPECT_EQ(s.source, "learnopengl:shadows");
  ASSERT_EQ(s.primitives.size(), overview.primitives.size() + 1);
  EXPECT_EQ(s.primitives.back().name, "floor");
  // The objects stand on the floor.
  for (size_t i = 0; i < overview.primitives.size(); ++i)
    EXPECT_FLOAT_EQ(s.primitives[i].bounds.min.y, s.primitives.back().bounds.max.y) << s.primitives[i].name;
  EXPECT_EQ(s.pointLights.size(), overview.pointLights.size());
  EXPECT_EQ(castingPointLights(s), 0u);
  ASSERT_EQ(s.directionalLights.size(), 1u);
  EXPECT_TRUE(s.directionalLights[0].castShadows);
  EXPECT_EQ(s.camera.position, overview.camera.position);
  // The overview itself is unchanged: no floor, no sun.
  EXPECT_TRUE(overview.directionalLights.empty());
  EXPECT_FALSE(overview.hasShadowCastingLights());
}

TEST(ShadowScenes, TheShadowsSceneHasEveryKindOfCasterAndLight) {
  const Scene s = loadSceneFile(std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json");
  size_t pillars = 0, posts = 0, spots = 0, shadowedPoints = 0, plainPoints = 0;
  for (const Primitive& p : s.primitives) {
    pillars += p.name.rfind("pillar", 0) == 0;
    posts += p.name.rfind("fence_post", 0) == 0;
    if (p.name == "glass") EXPECT_FALSE(s.castsShadows(p));
  }
  for (const PointLight& l : s.pointLights) {
    if (l.spot) spots += l.castsShadows();
    else (l.castsShadows() ? shadowedPoints : plainPoints)++;
  }
  EXPECT_GE(pillars, 4u);
  EXPECT_GE(posts, 10u);
  EXPECT_GE(spots, 2u);
  EXPECT_GE(shadowedPoints, 2u);
  EXPECT_GE(plainPoints, 1u);
  ASSERT_EQ(s.directionalLights.size(), 1u);
  EXPECT_TRUE(s.directionalLights[0].castShadows);
}
