// Scene files: the "spin" animation key (Primitive::Spin, transformAt) and its errors.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;

namespace {

class SceneSpin : public scenetest::TempDirTest {
 protected:
  std::string write(const std::string& text) {
    scenetest::writeText(path("spin.json"), text);
    return path("spin.json");
  }
  // The message of the RuntimeError loading `text` throws ("" and a test failure if none).
  std::string error(const std::string& text) {
    const std::string p = write(text);
    try {
      loadSceneFile(p);
      ADD_FAILURE() << "expected a RuntimeError for: " << text;
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "";
  }
};

void expectNear(const glm::vec3& a, const glm::vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

}  // namespace

TEST_F(SceneSpin, TurnsAboutTheModelOrigin) {
  const Scene s = loadSceneFile(write(R"({"models": [
    {"shape": "cube", "transform": {"translation": [2, 0, 0]}, "spin": {"axis": [0, 2, 0], "degrees_per_second": 90}},
    {"shape": "sphere"}]})"));
  ASSERT_EQ(s.primitives.size(), 2u);
  const Primitive& cube = s.primitives[0];
  EXPECT_TRUE(cube.animated());
  expectNear(cube.spin.pivot, {2, 0, 0});
  expectNear(cube.spin.axis, {0, 1, 0});  // normalised
  EXPECT_FLOAT_EQ(cube.spin.degreesPerSecond, 90.0f);
  // Time 0: the static transform; after 1 s a quarter turn about +Y through (2, 0, 0):
  // the local +X face centre (world (2.5, 0, 0)) goes to (2, 0, -0.5).
  expectNear(apply(cube.transformAt(0.0), {0.5f, 0, 0}), {2.5f, 0, 0});
  expectNear(apply(cube.transformAt(1.0), {0.5f, 0, 0}), {2.0f, 0, -0.5f});
  expectNear(apply(cube.transformAt(2.0), {0.5f, 0, 0}), {1.5f, 0, 0});
  // Whole turns vanish, however long the animation runs (the angle wraps in double).
  expectNear(apply(cube.transformAt(4.0 * 3600.0), {0.5f, 0, 0}), {2.5f, 0, 0});
  // The pivot itself does not move.
  expectNear(apply(cube.transformAt(0.7), {0, 0, 0}), {2, 0, 0});
  // A model without "spin" is static at any time.
  EXPECT_FALSE(s.primitives[1].animated());
  EXPECT_EQ(s.primitives[1].transformAt(3.0), s.primitives[1].transform);
}

TEST_F(SceneSpin, FollowsEditsOfTheTransform) {
  // transformAt starts from the current transform: moving a primitive through
  // the API moves the spinning model (its pivot stays where the file put it).
  Scene s = loadSceneFile(write(R"({"models": [{"shape": "cube", "spin": {"degrees_per_second": 180}}]})"));
  Primitive& p = s.primitives[0];
  expectNear(p.spin.axis, {0, 1, 0});  // default axis
  p.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 3, 0));
  expectNear(apply(p.transformAt(1.0), {0.5f, 0, 0}), {-0.5f, 3, 0});
}

TEST_F(SceneSpin, AppliesToEveryPrimitiveOfAFileModel) {
  scenetest::TriangleGltf t;
  t.writeGltf(path("tri.gltf"));
  const Scene s = loadSceneFile(write(R"({"models": [
    {"file": "tri.gltf", "transform": {"translation": [0, 0, -4]}, "spin": {"axis": [1, 0, 0], "degrees_per_second": -30}},
    {"file": "tri.gltf"}]})"));
  ASSERT_GE(s.primitives.size(), 2u);
  size_t animated = 0;
  for (const Primitive& p : s.primitives) {
    if (!p.animated()) continue;
    ++animated;
    expectNear(p.spin.pivot, {0, 0, -4});
    expectNear(p.spin.axis, {1, 0, 0});
    EXPECT_FLOAT_EQ(p.spin.degreesPerSecond, -30.0f);
  }
  EXPECT_EQ(animated, s.primitives.size() / 2);
}

TEST_F(SceneSpin, ErrorsNameFileLineColumnAndPointer) {
  const std::string file = path("spin.json");
  struct Case {
    const char* text;
    const char* where;  // file + this: line:col: pointer
    const char* what;
  };
  const Case cases[] = {
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"axis\": [0, 0, 0], \"degrees_per_second\": 90}}]}",
       ":2:20: /models/0/spin/axis", "non-zero"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"axis\": [1e39, 0, 0], \"degrees_per_second\": 90}}]}",
       ":2:20: /models/0/spin/axis", "finite"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"axis\": [0, 1, 0], \"degrees_per_second\": 1e39}}]}",
       ":2:53: /models/0/spin/degrees_per_second", "finite"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"degrees_per_second\": \"fast\"}}]}",
       ":2:34: /models/0/spin/degrees_per_second", "expected a number"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"axis\": [0, 1, 0]}}]}", ":2:11: /models/0/spin",
       "degrees_per_second"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": 90}]}", ":2:11: /models/0/spin", "expected an object"},
      {"{\"models\": [{\"shape\": \"cube\",\n  \"spin\": {\"axis\": [0, 1], \"degrees_per_second\": 1}}]}",
       ":2:20: /models/0/spin/axis", "3 numbers"},
  };
  for (const Case& c : cases) {
    const std::string msg = error(c.text);
    EXPECT_NE(msg.find(file + c.where), std::string::npos) << "expected '" << c.where << "' in: " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << "expected '" << c.what << "' in: " << msg;
  }
}
