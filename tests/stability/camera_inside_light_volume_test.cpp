// Case 1: the camera inside a light volume. Light volumes draw each light as
// a sphere of its cut-off radius; with back faces culled only the near side
// is drawn, and when the camera is inside the sphere that side is behind the
// camera: the light is lost. Front-face culling draws the far side and keeps
// it. Both are measured against the fullscreen deferred pass with the same
// cut-off (threshold 5/256), on the pixels the light reaches.
#include <algorithm>
#include <cmath>
#include <iostream>

#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;

namespace {

constexpr double kThreshold = 5.0 / 256.0;
constexpr Extent kSize{96, 96};

// A wall facing the camera (front face at z = 0, 8 x 8) and one point light
// between them.
Scene wallScene(glm::vec3 lightPos, float intensity) {
  Scene s;
  s.source = "test:wall";
  const int cube = addMesh(s, makeCube(1.0f));
  const int mat = addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.6f, 0.5f);
  addDraw(s, cube, mat, glm::scale(translate({0.0f, 0.0f, -0.25f}), glm::vec3(4.0f, 4.0f, 0.25f)), "wall");
  s.pointLights.push_back(pointLight(lightPos, {1.0f, 0.9f, 0.7f}, intensity));
  s.ambient = glm::vec3(0.05f);
  placeCamera(s, glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(0.0f, 0.0f, 0.0f), 60.0f, 0.05f, 20.0f);
  return s;
}

struct LightError {
  Diff diff;          // 8-bit error on the lit pixels
  double kept = 0.0;  // the light's energy the method kept: sum(method - ambient) / sum(reference - ambient)
};

LightError measure(const Frame& ref, const Frame& ambient, const Frame& method, const std::vector<bool>& lit) {
  LightError e;
  e.diff = compare8(ref.rgba, method.rgba, ref.size, &lit);
  const auto& r = ref.target("hdr");
  const auto& a = ambient.target("hdr");
  const auto& m = method.target("hdr");
  double want = 0.0, got = 0.0;
  for (size_t i = 0; i < lit.size(); ++i) {
    if (!lit[i]) continue;
    for (int c = 0; c < 3; ++c) {
      want += r[i * 4 + c] - a[i * 4 + c];
      got += m[i * 4 + c] - a[i * 4 + c];
    }
  }
  e.kept = want > 0.0 ? got / want : 0.0;
  return e;
}

struct Result {
  size_t litPixels = 0;
  LightError front, back;
  Diff frontAll, backAll;
};

Result run(const Scene& scene, const std::string& name) {
  const LightingParams l{"blinn_phong", "classic", kThreshold};
  Scene dark = scene;
  dark.pointLights.clear();
  const PipelineConfig full = pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "fullscreen");
  const Frame ref = renderFrame(full, scene, kSize, {"hdr"});
  const Frame ambient = renderFrame(full, dark, kSize, {"hdr"});
  const Frame front =
      renderFrame(pipelineFromJson(lightVolumesPipeline("front", l), "volumes-front"), scene, kSize, {"hdr"});
  const Frame back =
      renderFrame(pipelineFromJson(lightVolumesPipeline("back", l), "volumes-back"), scene, kSize, {"hdr"});

  // Lit pixels: where the light adds more than 1/255 to the reference.
  std::vector<bool> lit(static_cast<size_t>(kSize.width) * kSize.height, false);
  Result res;
  for (size_t i = 0; i < lit.size(); ++i) {
    for (int c = 0; c < 3; ++c)
      if (ref.target("hdr")[i * 4 + c] - ambient.target("hdr")[i * 4 + c] > 1.0f / 255.0f) lit[i] = true;
    res.litPixels += lit[i];
  }
  res.front = measure(ref, ambient, front, lit);
  res.back = measure(ref, ambient, back, lit);
  res.frontAll = compare8(ref.rgba, front.rgba, kSize);
  res.backAll = compare8(ref.rgba, back.rgba, kSize);
  std::cout << "[ measure  ] " << name << ": " << res.litPixels << " lit pixels of " << lit.size()
            << "\n             cull front: light kept " << res.front.kept * 100.0 << "%, lit pixels "
            << res.front.diff.describe() << "\n             cull back:  light kept " << res.back.kept * 100.0
            << "%, lit pixels " << res.back.diff.describe() << std::endl;
  if (res.front.diff.maxAbs > 2 || (name == "inside" && res.back.kept > 0.01)) {
    saveImage(ref.rgba, kSize, name + "-fullscreen");
    saveImage(front.rgba, kSize, name + "-cull-front");
    saveImage(back.rgba, kSize, name + "-cull-back");
  }
  return res;
}

}  // namespace

TEST_F(Stability, CameraInsideLightVolume) {
  // The light 1 unit in front of the wall, the camera 2 units: the camera is
  // 1 unit from the light, inside its ~5-unit volume.
  const Scene scene = wallScene({0.0f, 0.0f, 1.0f}, 1.0f);
  const float radius = lightRadius(scene.pointLights[0], static_cast<float>(kThreshold));
  ASSERT_GT(radius, 2.0f * glm::length(scene.camera.position - scene.pointLights[0].position))
      << "the camera must be well inside the light's volume";

  const Result r = run(scene, "inside");
  RecordProperty("lit_pixels", static_cast<int>(r.litPixels));
  RecordProperty("front_max_abs_8bit", r.front.diff.maxAbs);
  RecordProperty("front_light_kept_percent", std::to_string(r.front.kept * 100.0));
  RecordProperty("back_max_abs_8bit", r.back.diff.maxAbs);
  RecordProperty("back_light_kept_percent", std::to_string(r.back.kept * 100.0));
  ASSERT_GT(r.litPixels, kSize.width * kSize.height / 2) << "the light should reach most of the wall";

  // rgraph's answer (front faces culled, the default): the light is kept,
  // within 2/255 of the fullscreen pass everywhere (both add in rgba32f).
  EXPECT_LE(r.front.diff.maxAbs, 2) << r.front.diff.describe();
  EXPECT_LE(r.frontAll.maxAbs, 2) << r.frontAll.describe();
  EXPECT_NEAR(r.front.kept, 1.0, 0.005);
  // The documented failure of back-face culling: the near side of the sphere
  // is behind the camera, nothing is drawn, the light is lost entirely.
  EXPECT_LT(r.back.kept, 0.01) << "back-face culling was expected to lose the light";
  EXPECT_GE(r.back.diff.maxAbs, 64) << r.back.diff.describe();
}

TEST_F(Stability, CameraOutsideLightVolumeBothCullModesAgree) {
  // The control: a dim light (radius ~1.2) whose volume does not contain the
  // camera; both cull modes match the fullscreen pass. The failure above is
  // the camera being inside, not back-face culling as such.
  const Scene scene = wallScene({0.3f, -0.2f, 0.6f}, 0.1f);
  ASSERT_LT(lightRadius(scene.pointLights[0], static_cast<float>(kThreshold)),
            glm::length(scene.camera.position - scene.pointLights[0].position));
  const Result r = run(scene, "outside");
  ASSERT_GT(r.litPixels, 100u);
  EXPECT_LE(r.front.diff.maxAbs, 2) << r.front.diff.describe();
  EXPECT_LE(r.back.diff.maxAbs, 2) << r.back.diff.describe();
  EXPECT_NEAR(r.front.kept, 1.0, 0.005);
  EXPECT_NEAR(r.back.kept, 1.0, 0.005);
}
