// Scene files' "environment" (image-based lighting): the three kinds, the
// .hdr loader, the CLI's --environment values, and every error a user can
// make, named by file and JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;

namespace {

class SceneEnvironment : public scenetest::TempDirTest {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    scenetest::writeText(path(name), text);
    return path(name);
  }
  std::string errorOf(const std::string& text) {
    const std::string p = write("bad.json", text);
    try {
      loadSceneFile(p);
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "no error";
  }
  // A 4 x 2 equirectangular image: pixel i has radiance (i, 2i, 0.5).
  std::string writeHdr(const std::string& name) {
    std::vector<float> px;
    for (int i = 0; i < 8; ++i) px.insert(px.end(), {float(i), float(2 * i), 0.5f});
    EXPECT_TRUE(stbi_write_hdr(path(name).c_str(), 4, 2, 3, px.data()));
    return path(name);
  }
};

}  // namespace

TEST_F(SceneEnvironment, NoEnvironmentByDefault) {
  EXPECT_FALSE(loadSceneFile(write("s.json", R"({"lights": []})")).environment.has_value());
}

TEST_F(SceneEnvironment, UniformColourSkyAndIntensity) {
  Scene s = loadSceneFile(write("s.json", R"({"environment": {"color": [1, 0.5, 0.25], "intensity": 2}})"));
  ASSERT_TRUE(s.environment);
  EXPECT_EQ(s.environment->kind, Environment::Kind::uniform);
  EXPECT_EQ(environmentRadiance(*s.environment, {0, 1, 0}), glm::vec3(2.0f, 1.0f, 0.5f));

  s = loadSceneFile(write("t.json", R"({"environment": {"sky": {"sun_direction": [0, 2, 0], "sun_color": 100,
      "sun_radius_deg": 5, "zenith": [0, 0, 1], "horizon": [1, 1, 1], "ground": [0.5, 0, 0]}}})"));
  ASSERT_TRUE(s.environment);
  const Environment& e = *s.environment;
  EXPECT_EQ(e.kind, Environment::Kind::sky);
  EXPECT_EQ(e.sunDirection, glm::vec3(0, 1, 0));  // normalised
  EXPECT_FLOAT_EQ(e.sunRadiusDeg, 5.0f);
  // Straight up: the zenith colour plus the whole sun; far below: the ground.
  EXPECT_EQ(environmentRadiance(e, {0, 1, 0}), glm::vec3(100.0f, 100.0f, 101.0f));
  EXPECT_EQ(environmentRadiance(e, {0, -1, 0}), glm::vec3(0.5f, 0.0f, 0.0f));
  // At the horizon, away from the sun: the horizon colour.
  EXPECT_EQ(environmentRadiance(e, {1, 0, 0}), glm::vec3(1.0f));
}

TEST_F(SceneEnvironment, HdrFileRelativeToTheSceneFile) {
  writeHdr("sky.hdr");
  Scene s = loadSceneFile(write("s.json", R"({"environment": {"hdr": "sky.hdr", "intensity": 0.5}})"));
  ASSERT_TRUE(s.environment);
  const Environment& e = *s.environment;
  EXPECT_EQ(e.kind, Environment::Kind::hdr);
  EXPECT_EQ(e.width, 4u);
  EXPECT_EQ(e.height, 2u);
  // Pixel 6 (row 1, column 2): straight down at longitude 0 (-z) is row 1's column 2.
  const glm::vec3 down = environmentRadiance(e, glm::normalize(glm::vec3(0.0f, -1.0f, -0.01f)));
  EXPECT_NEAR(down.x, 3.0f, 0.05f);  // 6 * 0.5 (RGBE keeps ~1% precision)
  EXPECT_NEAR(down.y, 6.0f, 0.1f);
}

TEST_F(SceneEnvironment, ErrorsNameTheFileAndThePointer) {
  std::string m = errorOf(R"({"environment": {"hdr": "missing.hdr"}})");
  EXPECT_NE(m.find("bad.json:1:"), std::string::npos) << m;
  EXPECT_NE(m.find("/environment/hdr"), std::string::npos) << m;
  EXPECT_NE(m.find("missing.hdr: environment image not found"), std::string::npos) << m;

  write("garbage.hdr", "not a radiance file at all");
  m = errorOf(R"({"environment": {"hdr": "garbage.hdr"}})");
  EXPECT_NE(m.find("/environment/hdr"), std::string::npos) << m;
  EXPECT_NE(m.find("garbage.hdr: cannot read the environment image ("), std::string::npos) << m;

  m = errorOf(R"({"environment": {"color": 1, "sky": {}}})");
  EXPECT_NE(m.find("/environment: an environment needs exactly one of"), std::string::npos) << m;
  m = errorOf(R"({"environment": {}})");
  EXPECT_NE(m.find("/environment: an environment needs exactly one of"), std::string::npos) << m;
  m = errorOf(R"({"environment": {"color": 1, "intensity": -1}})");
  EXPECT_NE(m.find("/environment/intensity: must be >= 0"), std::string::npos) << m;
  m = errorOf(R"({"environment": {"color": [1, -1, 0]}})");
  EXPECT_NE(m.find("/environment/color"), std::string::npos) << m;
  m = errorOf(R"({"environment": {"sky": {"sun_radius_deg": 0}}})");
  EXPECT_NE(m.find("/environment/sky/sun_radius_deg: must be in (0, 45]"), std::string::npos) << m;
  m = errorOf(R"({"environment": {"sky": {"sun_direction": [0, 0, 0]}}})");
  EXPECT_NE(m.find("/environment/sky/sun_direction: must be a finite, non-zero vector"), std::string::npos) << m;
  m = errorOf(R"({"environment": "sky"})");
  EXPECT_NE(m.find("/environment: expected an object"), std::string::npos) << m;
}

TEST_F(SceneEnvironment, CommandLineSpecs) {
  EXPECT_EQ(environmentFromSpec("sky").kind, Environment::Kind::sky);
  const Environment c = environmentFromSpec("color:1,0.5,0");
  EXPECT_EQ(c.kind, Environment::Kind::uniform);
  EXPECT_EQ(c.color, glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_EQ(environmentFromSpec(writeHdr("e.hdr")).width, 4u);
  for (const char* bad : {"color:1,2", "color:1,2,-3", "color:a,b,c", "color:1,2,3,4"}) {
    try {
      environmentFromSpec(bad);
      ADD_FAILURE() << bad;
    } catch (const RuntimeError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("environment '") + bad + "'"), std::string::npos) << e.what();
    }
  }
  try {
    environmentFromSpec(path("nothing.hdr"));
    ADD_FAILURE();
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.hdr: environment image not found"), std::string::npos) << e.what();
  }
}
