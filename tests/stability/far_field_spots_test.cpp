// The far field (tiled_deferred and clustered_deferred with far_field) with
// spot lights: the lights a tile or cluster does not list are summed with
// their cone (include/far_field.glsl's farFieldAdd), not as point lights.
//
// The scene: a floor seen from above, and a ring of eight wide spot lights
// around the part of it in view, every one beyond its cut-off radius from
// every visible pixel (checked: at the cut-off the fullscreen loop adds
// nothing to the ambient-only frame), so that no list holds them and all
// their light reaches the image through the far field. Two cases:
// - "away": the cones point away from the region: the exact loop (threshold
//   0) adds nothing there (checked), while the same lights as point lights
//   would add their tails (checked); the far field must add nothing (within
//   1/255). A far field that ignored the cones fails here.
// - "at": the cones point at the region: the exact loop brightens it
//   (checked); the far field must match it within 2/255 (the far field is a
//   low-frequency approximation; measured 1/255) where the plain cut, which
//   adds nothing, is off by far more (checked).
#include <cmath>
#include <cstdio>

#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;
using nlohmann::json;

namespace {

constexpr Extent kSize{144, 96};
constexpr double kThreshold = 40.0 / 256.0;  // a short radius, so that the tails past it are large

PointLight spot(glm::vec3 pos, glm::vec3 dir) {
  PointLight l = pointLight(pos, {1.0f, 0.9f, 0.8f}, 3.0f, 1.0f, 0.7f, 1.8f);
  l.spot = true;
  l.direction = glm::normalize(dir);
  l.innerConeDeg = 35.0f;
  l.outerConeDeg = 50.0f;
  l.radius = lightRadius(l);
  return l;
}

// The floor, and the ring of spot lights aimed at (towards the region's
// middle, downwards) or away from (outwards, upwards) the region in view.
Scene ringScene(bool aimedAt) {
  Scene s;
  s.source = aimedAt ? "test:far-spots-at" : "test:far-spots-away";
  const int plane = addMesh(s, makePlane(40.0f, 40.0f));
  addDraw(s, plane, addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.8f, 0.2f), glm::mat4(1.0f), "floor");
  for (int i = 0; i < 8; ++i) {
    const float a = float(i) * 0.785398f;
    const glm::vec3 pos(6.5f * std::cos(a), 1.5f, 5.5f * std::sin(a) - 0.5f);
    const glm::vec3 toMiddle = glm::vec3(0.0f, 0.0f, -0.5f) - pos;
    s.pointLights.push_back(spot(pos, aimedAt ? toMiddle : glm::vec3(-toMiddle.x, 1.0f, -toMiddle.z)));
  }
  s.ambient = glm::vec3(0.03f);
  placeCamera(s, glm::vec3(0.0f, 3.0f, 0.3f), glm::vec3(0.0f, 0.0f, -0.5f), 50.0f, 0.1f, 40.0f);
  return s;
}

// `type` with far_field on, the rest as the fullscreen pipeline.
json farFieldPipeline(const std::string& type, const LightingParams& l) {
  return computePipeline(type, l, {{"far_field", true}});
}

Frame fullscreen(const Scene& scene, double threshold, const std::string& name) {
  return renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, {"blinn_phong", "classic", threshold}), name),
                     scene, kSize);
}

}  // namespace

TEST_F(Stability, FarFieldOfSpotLightsFollowsTheirCones) {
  const size_t pixels = size_t{kSize.width} * kSize.height;
  for (const bool at : {false, true}) {
    SCOPED_TRACE(at ? "aimed at the region" : "aimed away");
    const Scene scene = ringScene(at);
    Scene dark = scene, points = scene;
    dark.pointLights.clear();
    for (PointLight& p : points.pointLights) p.spot = false;
    const Frame ambient = fullscreen(dark, 0.0, "ambient");
    const Frame exact = fullscreen(scene, 0.0, "exact");
    // Every light is beyond its cut-off from every pixel: the cut adds nothing.
    const Diff cut = compare8(fullscreen(scene, kThreshold, "cut").rgba, ambient.rgba, kSize);
    ASSERT_LE(cut.maxAbs, 1) << "a light reaches the view within its radius: " << cut.describe();
    const Diff lit = compare8(exact.rgba, ambient.rgba, kSize);
    std::printf("[ measure  ] %s: the exact loop against ambient only: %s\n", at ? "at" : "away", lit.describe().c_str());
    if (at) {
      ASSERT_GE(pixelsBrighter(exact, ambient, 6), pixels / 2) << "the cones' tails must show";
    } else {
      ASSERT_LE(lit.maxAbs, 1) << "the cones must point away from every pixel";
      const size_t tails = pixelsBrighter(fullscreen(points, 0.0, "points"), ambient, 6);
      ASSERT_GE(tails, pixels / 2) << "as point lights their tails must show";
    }
    for (const char* type : {"tiled_deferred", "clustered_deferred"}) {
      const Frame f =
          renderFrame(pipelineFromJson(farFieldPipeline(type, {"blinn_phong", "classic", kThreshold}), type), scene, kSize);
      const Diff d = compare8(f.rgba, exact.rgba, kSize);
      std::printf("[ measure  ] %s: %s + far field against the exact loop: %s\n", at ? "at" : "away", type,
                  d.describe().c_str());
      EXPECT_LE(d.maxAbs, at ? 2 : 1) << type << ": " << d.describe() << "; saved "
                                      << saveImage(f.rgba, kSize, std::string("far-spots-") + type) << " and "
                                      << saveImage(exact.rgba, kSize, "far-spots-exact");
    }
  }
}
