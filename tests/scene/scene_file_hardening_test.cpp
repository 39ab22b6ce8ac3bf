// Scene files against hostile or careless input (issue 8): errors at
// file:line:column, number overflow, deep nesting, the light cap, a camera
// looking along its up vector, model material overrides, and bytes that must
// never crash parseSceneText.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::TriangleGltf;

namespace {

class SceneFileHardening : public scenetest::TempDirTest {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    scenetest::writeText(path(name), text);
    return path(name);
  }
  // Loads `text` as a scene file expecting a RuntimeError; returns its message.
  std::string error(const std::string& text, const std::string& name = "bad.json") {
    const std::string p = write(name, text);
    try {
      loadSceneFile(p);
      ADD_FAILURE() << "expected a RuntimeError";
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return {};
  }
};

void expectContains(const std::string& msg, const std::string& needle) {
  EXPECT_NE(msg.find(needle), std::string::npos) << "'" << needle << "' not in: " << msg;
}

}  // namespace

TEST_F(SceneFileHardening, ErrorsCarryLineAndColumn) {
  // The value at fault: line 3, column 35 ("[0, 0]").
  expectContains(error("{\n  \"lights\": [\n    {\"type\": \"point\", \"position\": [0, 0]}\n  ]\n}\n"),
                 path("bad.json") + ":3:35: /lights/0/position: expected an array of 3 numbers");
  // A missing key: the object that lacks it.
  expectContains(error("{\"camera\":\n  {\"target\": [0, 0, 0]}}"), path("bad.json") + ":2:3: /camera: a camera needs \"position\"");
  // The root.
  expectContains(error("  [1, 2]"), path("bad.json") + ":1:3: /: the scene file must be a JSON object");
  // Inside a model's material.
  expectContains(error(R"({"models": [{"shape": "cube", "material": {"metallic": 2}}]})"),
                 path("bad.json") + ":1:56: /models/0/material/metallic: must be in [0, 1]");
}

TEST_F(SceneFileHardening, NumberOverflowNamesTheFile) {
  // Was a bare "[json.exception.out_of_range.406] number overflow parsing '1e400'".
  expectContains(error("{\"ambient\": 1e400}"), path("bad.json") + ":1:13: invalid JSON: number overflow parsing '1e400'");
}

TEST_F(SceneFileHardening, DeepNestingIsRefusedBeforeParsing) {
  const std::string deep = "{\"extra\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
  // The root object is level 1: the 256th '[' (column 11 + 255) opens level 257.
  expectContains(error(deep), path("bad.json") + ":1:266: values nested deeper than 256 levels are not supported");
  // Unclosed, too (the parser never sees it).
  expectContains(error(std::string(100000, '[')), path("bad.json") + ":1:257: values nested deeper than 256");
  // 256 levels are fine (an unknown key, warned about).
  const std::string ok = "{\"extra\": " + std::string(255, '[') + std::string(255, ']') + ", \"lights\": []}";
  EXPECT_NO_THROW(loadSceneFile(write("ok.json", ok)));
}

TEST_F(SceneFileHardening, TooManyLightsAreRefusedBeforeParsingThem) {
  // 1,000,000 lights took 50 s and 2.5 GB; the cap is the many-lights:N one.
  const std::string light = "{\"type\": \"directional\", \"direction\": [0, -1, 0]}";
  std::string text = "{\"lights\": [\n";
  for (size_t i = 0; i < 1000000; ++i) text += (i ? ",\n" : "") + light;
  text += "]}";
  const auto start = std::chrono::steady_clock::now();
  const std::string msg = error(text);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Element 100000 (the 100,001st) starts line 100002.
  expectContains(msg, path("bad.json") + ":100002:1: /lights/100000: more than 100000 lights; a scene may have at most 100000");
  // The refusal comes from a byte scan, not a parse of 49 MB (about 15 s here): generous for sanitizers.
  EXPECT_LT(seconds, 5.0);
}

TEST_F(SceneFileHardening, ExactlyTheLightCapLoads) {
  std::string text = "{\"lights\": [";
  for (size_t i = 0; i < kMaxSceneLights; ++i) text += i ? ",{\"type\":\"directional\",\"direction\":[0,-1,0]}" : "{\"type\":\"directional\",\"direction\":[0,-1,0]}";
  text += "]}";
  EXPECT_EQ(parseSceneText(text, "cap.json", dir_.string()).directionalLights.size(), kMaxSceneLights);
}

TEST_F(SceneFileHardening, CameraUpParallelToTheViewIsReplacedWithAWarning) {
  scenetest::LogCapture log;
  // Straight down with the default up (0, 1, 0).
  const Scene s = loadSceneFile(write("top.json", R"({"models": [{"shape": "cube"}],
    "camera": {"position": [0, 5, 0], "target": [0, 0, 0]}})"));
  EXPECT_EQ(s.camera.up, glm::vec3(0, 0, -1));
  EXPECT_GT(glm::length(glm::cross(s.camera.forward(), s.camera.up)), 0.99f);
  expectContains(log.text(), path("top.json") + ":2:15: /camera: the up vector is parallel to the view direction; using up = [0");
  // An explicit up along the view direction: the warning points at it.
  const Scene s2 = loadSceneFile(write("along.json", R"({"camera": {"position": [0, 0, 5], "target": [0, 0, 0], "up": [0, 0, 2]}})"));
  EXPECT_EQ(s2.camera.up, glm::vec3(0, 1, 0));
  expectContains(log.text(), path("along.json") + ":1:63: /camera/up: the up vector is parallel");
}

TEST_F(SceneFileHardening, ModelMaterialOverridesGltfValues) {
  TriangleGltf t;
  t.doc["materials"] = nlohmann::json::parse(R"([{"pbrMetallicRoughness": {"metallicFactor": 0.9, "roughnessFactor": 0.3}}])");
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.writeGltf(path("tri.gltf"));
  const Scene plain = loadSceneFile(write("plain.json", R"({"models": [{"file": "tri.gltf"}]})"));
  ASSERT_EQ(plain.materials.size(), 1u);
  EXPECT_EQ(plain.materials[0].specular, 0.5f);  // glTF has no Blinn-Phong specular
  const Scene s = loadSceneFile(write("s.json", R"({"models": [
    {"file": "tri.gltf", "material": {"specular": 0.125, "metallic": 0}},
    {"file": "tri.gltf"}]})"));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].specular, 0.125f);
  EXPECT_EQ(s.materials[0].metallicFactor, 0.0f);
  EXPECT_EQ(s.materials[0].roughnessFactor, 0.3f);  // not given: the model's own
  EXPECT_EQ(s.materials[1].specular, 0.5f);          // the other model keeps its values
  EXPECT_EQ(s.materials[1].metallicFactor, 0.9f);
  // The same ranges as a shape's material.
  expectContains(error(R"({"models": [{"file": "tri.gltf", "material": {"specular": 3}}]})"),
                 ":1:59: /models/0/material/specular: must be in [0, 1]");
  expectContains(error(R"({"models": [{"shape": "cube", "material": {"baseColor": [1, 1.5, 1]}}]})"),
                 "/models/0/material/baseColor/1: must be in [0, 1]");
}

// Damaged scene files (truncations and byte flips of the shipped ones, and
// random bytes) load or throw RuntimeError: nothing else (run under ASan too).
TEST_F(SceneFileHardening, DamagedTextNeverCrashes) {
  const std::string base = std::string(RGRAPH_SOURCE_DIR) + "/scenes/";
  size_t refused = 0;
  auto attempt = [&](const std::string& text) {
    try {
      parseSceneText(text, "damaged.json", base);
    } catch (const RuntimeError&) {
      ++refused;
    }
  };
  for (const char* name : {"learnopengl.json"}) {  // (shapes only: no model loads per attempt)
    const std::vector<uint8_t> bytes = scenetest::readBytes(base + name);
    const std::string text(bytes.begin(), bytes.end());
    ASSERT_FALSE(text.empty()) << name;
    for (size_t len = 0; len < text.size(); len += 97) attempt(text.substr(0, len));
    uint32_t x = 7;
    for (int i = 0; i < 300; ++i) {
      std::string t = text;
      x = x * 1664525u + 1013904223u;
      t[(x >> 8) % t.size()] = char(x >> 24);
      attempt(t);
    }
  }
  uint32_t x = 3;
  for (int i = 0; i < 200; ++i) {
    std::string t(size_t(i * 7), '\0');
    for (char& c : t) c = char((x = x * 1664525u + 1013904223u) >> 24);
    attempt(t);
  }
  EXPECT_GT(refused, 200u);
}

TEST_F(SceneFileHardening, FoldersAreNamedAsSuch) {
  std::filesystem::create_directories(dir_ / "dir.json");
  std::filesystem::create_directories(dir_ / "dir.gltf");
  try {
    loadSceneFile(path("dir.json"));
    ADD_FAILURE() << "expected a RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_EQ(std::string(e.what()), path("dir.json") + ": is a folder, not a scene file");
  }
  expectContains(error(R"({"models": [{"file": "dir.gltf"}]})"),
                 ":1:22: /models/0/file: " + path("dir.gltf") + ": is a folder, not a glTF file");
}
