// Regression tests for what the scene and glTF fuzz targets found (issue 8,
// docs/fuzzing.md). Each input is the essence of a fuzzer reproducer, written
// out small. The finding: finite input numbers whose results are not usable
// loaded silently and rendered an empty frame:
//   - a glTF vertex at 9.6e25 (a flipped bit in a .glb's float): the framing
//     camera's near * far overflowed to infinity;
//   - a vertex at 2e12: the view matrix came out NaN, because the camera's
//     direction vanished in the float precision of its position;
//   - a node scale of 1e30 under another: the world transform overflowed;
//   - a scene-file camera with near 1e-38 and far 3e38: the projection overflowed.
// Now: world coordinates beyond kMaxWorldCoordinate and cameras whose
// view-projection is not finite are refused naming the file, and the view
// matrix is built so that it stays finite far from the origin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::TriangleGltf;

namespace {

bool finiteMatrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// The triangle, its second vertex moved to `x` on the X axis, as .glb bytes.
std::vector<uint8_t> triangleWithVertexAt(float x) {
  TriangleGltf t;
  std::memcpy(t.bin.data() + 12, &x, sizeof x);
  t.doc["accessors"][0]["max"] = {x, 1, 0};
  return TriangleGltf::makeGlb(t.glbJson(), t.bin);
}

std::string loadError(const std::vector<uint8_t>& bytes, const std::string& name) {
  try {
    loadGltfFromMemory(bytes.data(), bytes.size(), name, "");
  } catch (const RuntimeError& e) {
    return e.what();
  }
  ADD_FAILURE() << name << ": expected a RuntimeError";
  return {};
}

void expectContains(const std::string& msg, const std::string& needle) {
  EXPECT_NE(msg.find(needle), std::string::npos) << "'" << needle << "' not in: " << msg;
}

TEST(FuzzRegression, GltfVertexBeyondTheWorldLimitIsRefusedNamingTheFile) {
  const std::string msg = loadError(triangleWithVertexAt(9.6e25f), "flipped-bit.glb");
  expectContains(msg, "flipped-bit.glb: ");
  expectContains(msg, "primitive 0");
  expectContains(msg, "9.6e+25");
  expectContains(msg, "exceed +-1e+15 units");
}

TEST(FuzzRegression, GltfVertexJustInsideTheLimitLoads) {
  const std::vector<uint8_t> glb = triangleWithVertexAt(kMaxWorldCoordinate);
  EXPECT_EQ(loadGltfFromMemory(glb.data(), glb.size(), "edge.glb", "").triangleCount(), 1u);
}

TEST(FuzzRegression, GltfFarFromTheOriginIsFramedByAFiniteCameraThatSeesIt) {
  // The model spans 0..2e12 on X: the framing camera stands ~1e12 units away.
  const std::vector<uint8_t> glb = triangleWithVertexAt(2e12f);
  Scene scene = loadGltfFromMemory(glb.data(), glb.size(), "far.glb", "");
  applySceneDefaults(scene);
  const glm::mat4 vp = scene.camera.viewProjection(1.0f);
  ASSERT_TRUE(finiteMatrix(scene.camera.view()));
  ASSERT_TRUE(finiteMatrix(vp));
  // The bounds' centre lands in the middle of the frame, in front of the camera.
  const glm::vec4 clip = vp * glm::vec4(scene.bounds().center(), 1.0f);
  ASSERT_GT(clip.w, 0.0f);
  EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-3f);
  EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-3f);
  EXPECT_GT(clip.z / clip.w, -1.0f);
  EXPECT_LT(clip.z / clip.w, 1.0f);
}

TEST(FuzzRegression, GltfNodeScalesThatOverflowTogetherAreRefused) {
  TriangleGltf t;
  t.doc["scenes"][0]["nodes"] = {1};
  t.doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "scale": [1e30, 1e30, 1e30]},
                                              {"children": [0], "scale": [1e30, 1e30, 1e30]}])");
  const std::vector<uint8_t> glb = TriangleGltf::makeGlb(t.glbJson(), t.bin);
  const std::string msg = loadError(glb, "scaled.glb");
  expectContains(msg, "scaled.glb: ");
  expectContains(msg, "primitive 0");
  expectContains(msg, "world transform is not finite");
}

class FuzzRegressionSceneFile : public scenetest::TempDirTest {
 protected:
  std::string error(const std::string& text) {
    scenetest::writeText(path("fuzzed.json"), text);
    try {
      loadSceneFile(path("fuzzed.json"));
    } catch (const RuntimeError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected a RuntimeError for " << text;
    return {};
  }
};

TEST_F(FuzzRegressionSceneFile, TransformThatOverflowsIsRefused) {
  const std::string msg =
      error(R"({"models": [{"shape": "cube", "transform": {"translation": [3e38, 0, 0], "scale": 3e38}}]})");
  expectContains(msg, "fuzzed.json: ");
  expectContains(msg, "primitive 0 ('cube')");
  expectContains(msg, "exceed +-1e+15 units");
}

TEST_F(FuzzRegressionSceneFile, CameraWhoseProjectionOverflowsIsRefused) {
  const std::string msg = error(
      R"({"models": [{"shape": "cube"}], "camera": {"position": [0, 0, 5], "near": 1e-38, "far": 3e38}})");
  expectContains(msg, "fuzzed.json: ");
  expectContains(msg, "camera: its view and projection are not finite");
}

TEST_F(FuzzRegressionSceneFile, PointLightBeyondTheWorldLimitIsRefused) {
  const std::string msg =
      error(R"({"models": [{"shape": "cube"}], "lights": [{"type": "point", "position": [0, 2e15, 0]}]})");
  // Checked where the light is read (the ranges of rgraph/scene.h), so located.
  expectContains(msg, "fuzzed.json:1:74: /lights/0/position: (0, 2e+15, 0) exceeds +-1e+15 units");
}

TEST(FuzzRegression, ViewMatrixIsLookAtNearTheOriginAndFiniteFarFromIt) {
  // Near the origin the result is glm::lookAt's, as before.
  Camera near;
  near.position = {1.0f, 2.0f, 5.0f};
  near.target = {0.0f, 0.5f, -1.0f};
  const glm::mat4 expected = glm::lookAt(near.position, near.target, near.up);
  const glm::mat4 got = near.view();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], expected[c][r], 1e-5f) << c << "," << r;

  // 1.6e12 from the origin a unit step is below the float precision of the
  // position: the target still lies straight ahead, on -Z in view space.
  Camera far;
  far.position = {0.0f, 9.2e11f, 1.6e12f};
  far.target = {0.0f, 0.0f, -1.0e12f};
  const glm::mat4 v = far.view();
  ASSERT_TRUE(finiteMatrix(v));
  const glm::vec4 t = v * glm::vec4(far.target, 1.0f);
  const float dist = glm::length(far.target - far.position);
  EXPECT_NEAR(t.x / dist, 0.0f, 1e-4f);
  EXPECT_NEAR(t.y / dist, 0.0f, 1e-4f);
  EXPECT_NEAR(t.z / dist, -1.0f, 1e-4f);
}

}  // namespace
