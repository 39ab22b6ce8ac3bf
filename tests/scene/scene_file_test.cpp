// Scene files (JSON): parsing, transforms, relative paths, errors; the example scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::TriangleGltf;

namespace {

class SceneFile : public scenetest::TempDirTest {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    scenetest::writeText(path(name), text);
    return path(name);
  }
  // Expects loadSceneFile to throw a RuntimeError mentioning the file and every needle.
  void expectError(const std::string& text, std::initializer_list<std::string> needles) {
    const std::string p = write("bad.json", text);
    try {
      loadSceneFile(p);
      ADD_FAILURE() << "expected a RuntimeError for: " << text;
    } catch (const RuntimeError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(p), std::string::npos) << msg;
      for (const std::string& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
    }
  }
};

}  // namespace

TEST_F(SceneFile, ModelsLightsAmbientCamera) {
  std::filesystem::create_directories(dir_ / "models");
  TriangleGltf t;
  t.writeGltf(path("models/tri.gltf"));
  const std::string p = write("scene.json", R"({
    "models": [
      {"file": "models/tri.gltf", "transform": {"translation": [10, 0, 0], "rotation_euler_deg": [0, 90, 0], "scale": 2}},
      {"file": "models/tri.gltf"},
      {"shape": "cube", "material": {"baseColor": [1, 0, 0], "metallic": 0.5, "roughness": 0.25, "specular": 0.75},
       "transform": {"translation": [0, 0.5, 0]}},
      {"shape": "plane", "size": [20, 1, 10]}
    ],
    "lights": [
      {"type": "point", "position": [1, 2, 3], "color": [1, 0.5, 0.5], "intensity": 2, "constant": 1, "linear": 0.35, "quadratic": 0.44},
      {"type": "point", "position": [0, 1, 0], "radius": 4},
      {"type": "directional", "direction": [0, -2, 0], "color": [1, 1, 1], "intensity": 0.5}
    ],
    "ambient": [0.05, 0.05, 0.1],
    "camera": {"position": [0, 2, 8], "target": [0, 0, 0], "fov": 60, "near": 0.5, "far": 200}
  })");
  const Scene s = loadSceneFile(p);
  EXPECT_NO_THROW(s.validate());
  ASSERT_EQ(s.primitives.size(), 4u);
  // Model 0: translate * rotateY(90) * scale 2 applied to the glTF's own transform.
  const glm::vec3 w(s.primitives[0].transform * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(glm::distance(w, glm::vec3(10, 0, -2)), 0.0f, 1e-5f);
  EXPECT_EQ(s.primitives[1].transform, glm::mat4(1.0f));
  const Material& cube = s.materials[size_t(s.primitives[2].material)];
  EXPECT_EQ(cube.baseColorFactor, glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(cube.metallicFactor, 0.5f);
  EXPECT_EQ(cube.roughnessFactor, 0.25f);
  EXPECT_EQ(cube.specular, 0.75f);
  EXPECT_NEAR(s.primitives[2].bounds.min.y, 0.0f, 1e-6f);  // unit cube lifted by 0.5
  EXPECT_NEAR(s.primitives[3].bounds.size().x, 20.0f, 1e-5f);
  EXPECT_NEAR(s.primitives[3].bounds.size().z, 10.0f, 1e-5f);

  ASSERT_EQ(s.pointLights.size(), 2u);
  const PointLight& l = s.pointLights[0];
  EXPECT_EQ(l.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(l.intensity, 2.0f);
  EXPECT_EQ(l.linear, 0.35f);
  EXPECT_EQ(l.quadratic, 0.44f);
  EXPECT_EQ(l.radius, lightRadius(l));
  EXPECT_EQ(s.pointLights[1].radius, 4.0f);
  EXPECT_EQ(s.pointLights[1].linear, 0.7f);  // defaults: the LearnOpenGL attenuation
  ASSERT_EQ(s.directionalLights.size(), 1u);
  EXPECT_EQ(s.directionalLights[0].direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(s.ambient, glm::vec3(0.05f, 0.05f, 0.1f));
  ASSERT_TRUE(s.hasCamera);
  EXPECT_EQ(s.camera.position, glm::vec3(0, 2, 8));
  EXPECT_EQ(s.camera.fovY, 60.0f);
  EXPECT_EQ(s.camera.near, 0.5f);
  EXPECT_EQ(s.camera.far, 200.0f);
  EXPECT_TRUE(s.hasMetallicRoughnessVariation());  // factors differ between materials
}

TEST_F(SceneFile, DefaultsWhenCameraAndLightsAreMissing) {
  TriangleGltf t;
  t.writeGltf(path("tri.gltf"));
  const Scene s = loadSceneFile(write("s.json", R"({"models": [{"file": "tri.gltf"}], "ambient": 0.2})"));
  EXPECT_TRUE(s.hasCamera);
  EXPECT_EQ(s.directionalLights.size(), 1u);  // default light
  EXPECT_EQ(s.ambient, glm::vec3(0.2f));
  // "lights": [] means no lights.
  const Scene dark = loadSceneFile(write("d.json", R"({"models": [{"file": "tri.gltf"}], "lights": []})"));
  EXPECT_TRUE(dark.directionalLights.empty());
  EXPECT_TRUE(dark.pointLights.empty());
}

TEST_F(SceneFile, AbsolutePathsAndLoadSceneAny) {
  const std::string box = scenetest::asset("Box/Box.glb");
  const Scene s = loadSceneAny(write("abs.json", R"({"models": [{"file": ")" + box + R"("}]})"));
  EXPECT_EQ(s.triangleCount(), 12u);
  EXPECT_EQ(s.source, path("abs.json"));
}

TEST_F(SceneFile, LightWithoutFalloffGetsAFiniteRadius) {
  const Scene s = loadSceneFile(write("s.json", R"({
    "models": [{"shape": "plane", "size": 10}],
    "lights": [{"type": "point", "position": [0, 1, 0], "linear": 0, "quadratic": 0}],
    "camera": {"position": [0, 5, 5], "far": 20}
  })"));
  ASSERT_EQ(s.pointLights.size(), 1u);
  EXPECT_TRUE(std::isfinite(s.pointLights[0].radius));
  EXPECT_GE(s.pointLights[0].radius, 20.0f);
}

TEST_F(SceneFile, BadJsonReportsLineAndColumn) {
  const std::string p = write("broken.json", "{\n  \"models\": [\n    {\"file\": \"a.gltf\",}\n  ]\n}\n");
  try {
    loadSceneFile(p);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p + ":3:"), std::string::npos) << msg;
  }
}

TEST_F(SceneFile, Errors) {
  expectError("[1, 2]", {"object"});
  expectError(R"({"models": {}})", {"/models", "array"});
  expectError(R"({"models": [{"file": "nowhere.gltf"}]})", {"/models/0/file", "nowhere.gltf"});
  expectError(R"({"models": [{"file": 3}]})", {"/models/0/file", "string"});
  expectError(R"({"models": [{"shape": "cube", "material": {"doubleSided": 1}}]})",
              {"/models/0/material/doubleSided", "expected true or false, got number"});
  expectError(R"({"models": [{}]})", {"/models/0", "file"});
  expectError(R"({"models": [{"shape": "torus"}]})", {"/models/0/shape", "torus"});
  expectError(R"({"models": [{"shape": "cube", "transform": {"scale": [1, 2]}}]})", {"/models/0/transform/scale"});
  expectError(R"({"models": [{"shape": "cube", "transform": {"translation": [1, "x", 2]}}]})", {"/models/0/transform/translation/1", "number"});
  expectError(R"({"models": [{"shape": "cube", "material": {"metallic": 2}}]})", {"/models/0/material/metallic"});
  expectError(R"({"lights": [{"type": "area", "position": [0, 0, 0]}]})", {"/lights/0/type", "area", "spot"});
  expectError(R"({"lights": [{"type": "point"}]})", {"/lights/0", "position"});
  expectError(R"({"lights": [{"type": "point", "position": [0, 0]}]})", {"/lights/0/position"});
  expectError(R"({"lights": [{"type": "point", "position": [0, 0, 0], "linear": -1}]})", {"/lights/0/linear"});
  expectError(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})", {"/lights/0/direction"});
  expectError(R"({"lights": [{"position": [0, 0, 0]}]})", {"/lights/0", "type"});
  expectError(R"({"ambient": "bright"})", {"/ambient"});
  expectError(R"({"camera": {"position": [0, 0, 5], "fov": 0}})", {"/camera/fov"});
  expectError(R"({"camera": {"position": [0, 0, 5], "near": 1, "far": 0.5}})", {"/camera/far"});
  expectError(R"({"camera": {"target": [0, 0, 0]}})", {"/camera", "position"});
  expectError(R"({"camera": {"position": [0, 0, 5], "target": [0, 0, 5]}})", {"/camera/target"});
}

TEST_F(SceneFile, BrokenModelNamesBothFiles) {
  scenetest::writeText(path("broken.gltf"), "{ not json");
  const std::string p = write("s.json", R"({"models": [{"file": "broken.gltf"}]})");
  try {
    loadSceneFile(p);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p), std::string::npos) << msg;
    EXPECT_NE(msg.find("broken.gltf"), std::string::npos) << msg;
    EXPECT_NE(msg.find("/models/0/file"), std::string::npos) << msg;
  }
}

TEST_F(SceneFile, MissingSceneFile) {
  EXPECT_THROW(loadSceneFile(path("none.json")), RuntimeError);
  EXPECT_THROW(loadSceneAny(path("none.json")), RuntimeError);
  EXPECT_THROW(loadSceneAny(path("none.glb")), RuntimeError);
}

TEST(ExampleScenes, AllLoad) {
  const std::filesystem::path dir = std::filesystem::path(RGRAPH_SOURCE_DIR) / "scenes";
  size_t count = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    const Scene s = loadSceneAny(e.path().string());
    EXPECT_NO_THROW(s.validate());
    EXPECT_GT(s.triangleCount(), 0u);
    EXPECT_TRUE(s.hasCamera);
    ++count;
  }
  EXPECT_GE(count, 2u);
}

// scenes/learnopengl.json spells out the procedural learnopengl scene.
TEST(ExampleScenes, LearnOpenGLJsonMatchesTheProceduralScene) {
  const Scene file = loadSceneFile(std::string(RGRAPH_SOURCE_DIR) + "/scenes/learnopengl.json");
  const Scene proc = makeLearnOpenGLScene();
  ASSERT_EQ(file.pointLights.size(), proc.pointLights.size());
  for (size_t i = 0; i < proc.pointLights.size(); ++i) {
    EXPECT_NEAR(glm::distance(file.pointLights[i].position, proc.pointLights[i].position), 0.0f, 1e-5f) << i;
    EXPECT_NEAR(glm::distance(file.pointLights[i].color, proc.pointLights[i].color), 0.0f, 1e-5f) << i;
    EXPECT_NEAR(file.pointLights[i].radius, proc.pointLights[i].radius, 1e-4f) << i;
  }
  ASSERT_EQ(file.primitives.size(), proc.primitives.size());
  for (size_t i = 0; i < proc.primitives.size(); ++i)
    EXPECT_NEAR(glm::distance(file.primitives[i].bounds.center(), proc.primitives[i].bounds.center()), 0.0f, 1e-5f) << i;
  EXPECT_EQ(file.camera.position, proc.camera.position);
  EXPECT_EQ(file.ambient, proc.ambient);
}

TEST_F(SceneFile, SpotLights) {
  const std::string p = write("spots.json", R"({
    "models": [{"shape": "plane", "size": 10}],
    "lights": [
      {"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0], "inner_cone_deg": 10, "outer_cone_deg": 30,
       "color": [1, 0.5, 0.5], "intensity": 2, "linear": 0.35, "quadratic": 0.44},
      {"type": "spot", "position": [1, 3, 0], "direction": [1, -1, 0], "radius": 6},
      {"type": "point", "position": [0, 1, 0]}
    ]
  })");
  const Scene s = loadSceneFile(p);
  ASSERT_EQ(s.pointLights.size(), 3u);
  const PointLight& a = s.pointLights[0];
  EXPECT_TRUE(a.spot);
  EXPECT_EQ(a.position, glm::vec3(0, 3, 0));
  EXPECT_NEAR(glm::distance(a.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);  // normalised
  EXPECT_EQ(a.innerConeDeg, 10.0f);
  EXPECT_EQ(a.outerConeDeg, 30.0f);
  EXPECT_EQ(a.intensity, 2.0f);
  EXPECT_EQ(a.linear, 0.35f);
  // The cone's reach is the same cut-off radius a point light would have.
  EXPECT_NEAR(a.radius, lightRadius(a), 1e-6f);
  // Defaults: glTF's cone (inner 0, outer 45 degrees).
  const PointLight& b = s.pointLights[1];
  EXPECT_TRUE(b.spot);
  EXPECT_EQ(b.innerConeDeg, 0.0f);
  EXPECT_EQ(b.outerConeDeg, 45.0f);
  EXPECT_EQ(b.radius, 6.0f);
  EXPECT_NEAR(glm::distance(b.direction, glm::normalize(glm::vec3(1, -1, 0))), 0.0f, 1e-6f);
  EXPECT_FALSE(s.pointLights[2].spot);
}

TEST_F(SceneFile, SpotLightErrorsNameLineColumnAndPointer) {
  const std::string spot = R"({"type": "spot", "position": [0, 1, 0], )";
  expectError(R"({"lights": [{"type": "spot", "position": [0, 1, 0]}]})", {"/lights/0", "a spot light needs \"direction\""});
  expectError(R"({"lights": [{"type": "spot", "direction": [0, -1, 0]}]})", {"/lights/0", "needs \"position\""});
  expectError("{\"lights\": [" + spot + R"("direction": [0, 0, 0]}]})", {"/lights/0/direction", "finite, non-zero"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1]}]})", {"/lights/0/direction", "3 numbers"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1, 0], "outer_cone_deg": 0}]})",
              {"/lights/0/outer_cone_deg", "(0, 90]"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1, 0], "outer_cone_deg": 91}]})",
              {"/lights/0/outer_cone_deg", "(0, 90]"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1, 0], "inner_cone_deg": -1}]})",
              {"/lights/0/inner_cone_deg", "less than outer_cone_deg (45"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1, 0], "inner_cone_deg": 30, "outer_cone_deg": 30}]})",
              {"/lights/0/inner_cone_deg", "less than outer_cone_deg (30"});
  expectError("{\"lights\": [" + spot + R"("direction": [0, -1, 0], "outer_cone_deg": "wide"}]})",
              {"/lights/0/outer_cone_deg", "number"});

  // file:line:column points at the value.
  const std::string p = write("cone.json", "{\"lights\": [\n  {\"type\": \"spot\", \"position\": [0, 1, 0],\n"
                                           "   \"direction\": [0, -1, 0], \"outer_cone_deg\": 120}]}");
  try {
    loadSceneFile(p);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p + ":3:47: /lights/0/outer_cone_deg"), std::string::npos) << msg;
  }
}

TEST_F(SceneFile, SpotDirectionTurnsWithTheModelTransform) {
  // A glTF model's spot light, turned by the scene file's transform.
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  t.doc["extensions"]["KHR_lights_punctual"]["lights"] =
      nlohmann::json::parse(R"([{"type": "spot", "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.3}}])");
  t.doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "children": [1]}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}])");
  t.writeGltf(path("spot.gltf"));
  const std::string p = write("turned.json", R"({"models": [{"file": "spot.gltf", "transform": {"rotation_euler_deg": [0, 90, 0]}}]})");
  const Scene s = loadSceneFile(p);
  ASSERT_EQ(s.pointLights.size(), 1u);
  ASSERT_TRUE(s.pointLights[0].spot);
  // -Z turned 90 degrees about +Y points along -X.
  EXPECT_NEAR(glm::distance(s.pointLights[0].direction, glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
}
