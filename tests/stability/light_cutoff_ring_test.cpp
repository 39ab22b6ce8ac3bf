// Case 4: the ring where a light is cut off at its radius. A light's radius
// is where its brightest channel falls to `threshold`; beyond it the light is
// dropped, so its contribution jumps from threshold * (albedo * N.L + specular)
// to 0 there. A floor lit by one white point light 2 units above it (albedo
// 0.8, no specular), rendered with the cut-off and without (threshold 0),
// fullscreen deferred lighting (fp32 G-buffer, rgba32f HDR) and linear 8-bit
// output (tonemap none, gamma 1, like the repo's LearnOpenGL pipelines). On
// the floor N.L at the ring is h / r, so the largest jump is
//   threshold * albedo * h / r          (HDR, linear)
// and its 8-bit image about 255 times that; never more than threshold * 255 *
// albedo (+1 for rounding) whatever the geometry.
#include <algorithm>
#include <cmath>
#include <iostream>

#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;

namespace {

constexpr Extent kSize{128, 128};
constexpr float kAlbedo = 0.8f;
constexpr float kHeight = 2.0f;

Scene floorScene() {
  Scene s;
  s.source = "test:floor";
  const int plane = addMesh(s, makePlane(14.0f, 14.0f));
  addDraw(s, plane, addMaterial(s, {kAlbedo, kAlbedo, kAlbedo, 1.0f}, 0.0f, 1.0f, /*specular=*/0.0f), glm::mat4(1.0f),
          "floor");
  s.pointLights.push_back(pointLight({0.0f, kHeight, 0.0f}, {1.0f, 1.0f, 1.0f}, 1.0f));  // LearnOpenGL: 1, 0.7, 1.8
  s.ambient = glm::vec3(0.02f);
  placeCamera(s, glm::vec3(0.0f, 26.0f, 0.0f), glm::vec3(0.0f), 60.0f, 1.0f, 40.0f, glm::vec3(0.0f, 0.0f, -1.0f));
  return s;
}

}  // namespace

TEST_F(Stability, LightCutoffRingPerThreshold) {
  const Scene scene = floorScene();
  const PointLight& light = scene.pointLights[0];
  const Frame ref = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, {"blinn_phong", "classic", 0.0}),
                                                 "no-cutoff"),
                                scene, kSize, {"hdr", "gPosition"});
  const auto& pos = ref.target("gPosition");
  // The same with the sRGB curve (tonemap gamma 0), for comparison: dark
  // rings are steeper there.
  const Frame refSrgb = renderFrame(
      pipelineFromJson(fullscreenPipeline({"fp32", ""}, {"blinn_phong", "classic", 0.0}, 0.0), "no-cutoff-srgb"), scene,
      kSize);
  for (const double threshold : {1.0 / 256.0, 5.0 / 256.0, 20.0 / 256.0}) {
    const std::string name = std::to_string(static_cast<int>(std::lround(threshold * 256.0))) + "/256";
    const float radius = lightRadius(light, static_cast<float>(threshold));
    ASSERT_GT(radius, kHeight) << name << ": the volume must reach the floor";
    const double ringOnFloor = std::sqrt(double(radius) * radius - double(kHeight) * kHeight);
    // The picture shows the floor out to ~15 units from the centre; the ring must be on it.
    ASSERT_LT(ringOnFloor, 13.0) << name;
    const Frame cut = renderFrame(
        pipelineFromJson(fullscreenPipeline({"fp32", ""}, {"blinn_phong", "classic", threshold}), "cutoff-" + name),
        scene, kSize, {"hdr"});

    const Frame cutSrgb = renderFrame(
        pipelineFromJson(fullscreenPipeline({"fp32", ""}, {"blinn_phong", "classic", threshold}, 0.0), "srgb-" + name),
        scene, kSize);
    int jumpSrgb = 0;
    for (size_t i = 0; i < cutSrgb.rgba.size(); ++i)
      if (i % 4 != 3) jumpSrgb = std::max(jumpSrgb, int(refSrgb.rgba[i]) - int(cutSrgb.rgba[i]));

    // Largest jump, in HDR and in 8 bits, and where it is.
    double hdrJump = 0.0, jumpDistance = 0.0, insideDiff = 0.0;
    int jump8 = 0;
    size_t ringPixels = 0;
    for (size_t i = 0; i < pos.size() / 4; ++i) {
      if (pos[i * 4 + 3] <= 0.0f) continue;  // background
      const double d = glm::length(glm::dvec3(pos[i * 4], pos[i * 4 + 1], pos[i * 4 + 2]) - glm::dvec3(light.position));
      double pixel = 0.0;
      int pixel8 = 0;
      for (int c = 0; c < 3; ++c) {
        pixel = std::max(pixel, double(ref.target("hdr")[i * 4 + c]) - cut.target("hdr")[i * 4 + c]);
        pixel8 = std::max(pixel8, int(ref.rgba[i * 4 + c]) - int(cut.rgba[i * 4 + c]));
      }
      if (d < radius * 0.999) insideDiff = std::max(insideDiff, std::abs(pixel));
      if (pixel > hdrJump) {
        hdrJump = pixel;
        jumpDistance = d;
      }
      jump8 = std::max(jump8, pixel8);
      ringPixels += d >= radius && d < radius + 0.3;
    }
    const double predicted = threshold * kAlbedo * kHeight / radius;  // at the ring, approached from outside
    const double bound8 = threshold * 255.0 * kAlbedo;                // any N.L
    std::cout << "[ measure  ] cut-off " << name << ": radius " << radius << " (ring " << ringOnFloor
              << " from the light's foot, N.L there " << kHeight / radius << "); largest jump: HDR " << hdrJump
              << " at distance " << jumpDistance << " (predicted " << predicted << "), 8-bit " << jump8
              << "/255 (predicted " << predicted * 255.0 << ", bound threshold*255*albedo " << bound8
              << "); inside the radius max diff " << insideDiff << "; with the sRGB curve instead: " << jumpSrgb
              << "/255" << std::endl;
    const std::string key = "threshold_" + std::to_string(static_cast<int>(std::lround(threshold * 256.0))) + "_256";
    RecordProperty(key + "_jump_8bit", jump8);
    RecordProperty(key + "_jump_hdr", std::to_string(hdrJump));
    RecordProperty(key + "_predicted_hdr", std::to_string(predicted));
    RecordProperty(key + "_jump_8bit_srgb", jumpSrgb);

    ASSERT_GT(ringPixels, 20u) << name << ": the ring should be in the picture";
    // Inside the radius the two are the same computation.
    EXPECT_EQ(insideDiff, 0.0) << name;
    // The jump happens at the radius ...
    EXPECT_GE(jumpDistance, radius * 0.999) << name;
    EXPECT_LE(jumpDistance, radius + 0.3) << name;
    // ... and is what the threshold allows: at most threshold * albedo * N.L,
    // and within 10% of it (the nearest pixel centres lie a little outside).
    EXPECT_LE(hdrJump, predicted * 1.0001) << name;
    EXPECT_GE(hdrJump, predicted * 0.9) << name;
    EXPECT_LE(std::abs(jump8 - predicted * 255.0), 1.0) << name;
    EXPECT_LE(jump8, std::ceil(bound8) + 1) << name;
  }
}
