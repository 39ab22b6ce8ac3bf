// ssao_upsample (plugins/ssao/shaders/ssao_upsample.frag) against its
// definition: a pixel at view depth z blends the 2x2 half-size texels around
// it with bilinear weights times exp(-(dz / (z * tolerance))^2), dz the view
// depth of the G-buffer texel each was computed from minus z.
//
// The scene: a square plane at z = 0 in front of a large plane at z = -2,
// seen from z = 5: a depth step of 2 (40% of the near depth) along the
// square's outline. The half-size visibility is a test image (oracle_ao_edge
// .frag) with 0.2 on texels computed on the near plane and 0.9 on the far
// one, so the right answer at each pixel is known: its own plane's value.
// Across the step a texel's weight is exp(-(0.4 / 0.05)^2) = e^-64, so the
// result is its plane's value to float rounding (tolerance 1e-4); a plain
// bilinear upsample (what deferred_lighting's 'ao' sampling does with a
// half-size input) mixes the two planes there (by up to 0.57 of the step 0.7
// in this view).
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "plugin_oracle.h"
#include "render/test_scenes.h"

using namespace rgraph;
using namespace rgraph::poracle;
using rgraph::rtest::addDraw;
using rgraph::rtest::addMaterial;
using rgraph::rtest::addMesh;

namespace {

constexpr int kSize = 128;
constexpr double kNear = 0.2, kFar = 0.9;

// clang-format off
const char* kConfig = R"({
  "version": 1,
  "resources": {
    "gPosition": { "format": "rgba32f" }, "gNormal": { "format": "rgba16f" },
    "gAlbedo": { "format": "rgba16f" }, "gMaterial": { "format": "rgba16f" }, "gDepth": { "format": "depth32f" },
    "ao_low": { "format": "r32f", "size": { "scale": 0.5 } }, "ao": { "format": "r32f" } },
  "passes": [
    { "name": "gbuffer", "type": "geometry", "params": { "layout": "pbr" },
      "outputs": { "position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial",
                   "depth": "gDepth" } },
    { "name": "low", "type": "fullscreen",
      "params": { "shader": "oracle_ao_edge.frag", "color": [0.2, 0.9, 0, 0], "value": -1.0 },
      "inputs": { "input0": "gPosition" }, "outputs": { "color": "ao_low" } },
    { "name": "upsample", "type": "ssao_upsample", "params": { "layout": "pbr", "tolerance": 0.05 },
      "inputs": { "src": "ao_low", "position": "gPosition" }, "outputs": { "ao": "ao" } }
  ],
  "output": "ao"
})";
// clang-format on

Scene stepScene() {
  Scene s;
  s.source = "test:ssao-upsample";
  const int mat = addMaterial(s, glm::vec4(0.8f), 0.0f, 0.5f);
  const glm::mat4 facing = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1, 0, 0));  // +Y -> +Z
  addDraw(s, addMesh(s, makePlane(1.1f, 1.1f)), mat, facing);
  addDraw(s, addMesh(s, makePlane(20.0f, 20.0f)), mat, glm::translate(glm::mat4(1.0f), {0, 0, -2}) * facing);
  s.camera.position = {0.1f, 0.07f, 5.0f};  // off-centre: the outline falls at odd and even pixels
  s.camera.target = {0.1f, 0.07f, 0.0f};
  s.camera.up = {0, 1, 0};
  s.camera.fovY = 45.0f;
  s.camera.near = 0.1f;
  s.camera.far = 50.0f;
  s.hasCamera = true;
  return s;
}

class OracleSsaoUpsample : public PluginOracleTest {};

}  // namespace

TEST_F(OracleSsaoUpsample, KeepsEachPlanesVisibilityAcrossADepthStep) {
  const Scene scene = stepScene();
  auto r = render(kConfig, {kSize, kSize}, {"gPosition", "ao", "ao_low"}, &scene);
  const Plane& z = r.at("gPosition").c[2];
  const Plane& w = r.at("gPosition").c[3];
  const Plane& ao = r.at("ao").c[0];
  const Plane& low = r.at("ao_low").c[0];  // square: side sqrt(texels) = 64
  ASSERT_EQ(low.width, kSize / 2);
  size_t nearPixels = 0, farPixels = 0, edgePixels = 0;
  double worst = 0.0, worstBilinear = 0.0;
  for (int row = 0; row < kSize; ++row)
    for (int x = 0; x < kSize; ++x) {
      ASSERT_EQ(w.at(x, row), 1.0) << "the far plane covers the view";
      const bool onNear = z.at(x, row) > -1.0;
      (onNear ? nearPixels : farPixels)++;
      const double want = onNear ? kNear : kFar;
      worst = std::max(worst, std::abs(ao.at(x, row) - want));
      // The plain bilinear upsample at this pixel (rows top-down in both images).
      const double sx = (x + 0.5) / 2.0 - 0.5, sy = (row + 0.5) / 2.0 - 0.5;
      const int bx = int(std::floor(sx)), by = int(std::floor(sy));
      const double fx = sx - bx, fy = sy - by;
      auto at = [&](int i, int j) { return low.at(std::clamp(i, 0, low.width - 1), std::clamp(j, 0, low.width - 1)); };
      const double bilinear = (1 - fy) * ((1 - fx) * at(bx, by) + fx * at(bx + 1, by)) +
                              fy * ((1 - fx) * at(bx, by + 1) + fx * at(bx + 1, by + 1));
      const double e = std::abs(bilinear - want);
      worstBilinear = std::max(worstBilinear, e);
      edgePixels += e > 0.05 ? 1 : 0;
    }
  std::printf("near %zu, far %zu pixels; worst error %.2e (bilinear: %.3f, off by > 0.05 at %zu pixels)\n", nearPixels,
              farPixels, worst, worstBilinear, edgePixels);
  ASSERT_GT(nearPixels, size_t(kSize * kSize / 10)) << "the near square must be in view";
  ASSERT_GT(farPixels, size_t(kSize * kSize / 4));
  EXPECT_LE(worst, 1e-4);
  EXPECT_GT(worstBilinear, 0.15) << "the scene must have edges a plain upsample gets wrong";
  EXPECT_GT(edgePixels, 100u);
}
