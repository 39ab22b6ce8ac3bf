// EVSM (shadow_filter evsm: the shadow_moments pass and shadows.glsl's
// Chebyshev bound) measured (issue 28): against exact visibility away from
// edges, its light leaking where casters overlap (bounded, and larger with
// the bleeding reduction off), and its moments blurred and mip-mapped as the
// pass says (read back from the moments texture).
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rgraph/gl/executor.h"
#include "shadow_probe.h"

namespace {
using namespace rgraph;
using shadows::LightKind;
using shadowtest::agreement;
using shadowtest::ProbeOptions;
using shadowtest::ProbeResult;

class ShadowEvsm : public rtest::RenderTest {};

// A moments texel spans 4 map texels (512 of 2048), the 5-tap box blur
// reaches 2.5 of them either side, and a mip level doubles that: probes
// within 24 map texels of an edge are left out.
constexpr double kEdgeTexels = 24.0;

ProbeOptions evsm() {
  ProbeOptions o;
  o.filter = "evsm";
  o.edgeTexels = kEdgeTexels;
  return o;
}

void expectAgreement(const shadowtest::Agreement& a, int minShadowed) {
  EXPECT_GE(a.lit, 1000);
  EXPECT_GE(a.shadowed, minShadowed);
  EXPECT_GE(a.share(), 0.995);
}

TEST_F(ShadowEvsm, DirectionalSpotAndPointAgreeWithExactVisibilityAwayFromEdges) {
  Scene sun = shadowtest::testScene();
  sun.directionalLights.push_back(shadowtest::sun());
  expectAgreement(agreement(sun, sun.directionalLights[0], {LightKind::directional, 0, 0, 4}, evsm(),
                            "evsm-directional"),
                  100);
  Scene spot = shadowtest::testScene();
  spot.pointLights.push_back(shadowtest::spot());
  expectAgreement(agreement(spot, spot.pointLights[0], {LightKind::spot, 0, 0, 1}, evsm(), "evsm-spot"), 100);
  Scene point = shadowtest::testScene();
  point.pointLights.push_back(shadowtest::point());
  expectAgreement(agreement(point, point.pointLights[0], {LightKind::point, 0, 0, 6}, evsm(), "evsm-point"), 100);
}

// Light leaking: a small box floating above a larger one that rests on the
// floor, under a sun leaning towards the camera. The floor behind the large
// box is in shadow, but where the moments' filter region holds both boxes'
// depths the variance is large, and near the large box's foot the floor's
// depth is close to its occluder's: there the Chebyshev bound lets light
// through. Measured over the floor probes the oracle says are shadowed: the
// mean light level (shadowed over unshadowed), the worst, and the share of
// probes brighter than 5% of unshadowed.
struct Leak {
  int shadowed = 0, leaking = 0;
  double light = 0.0, worst = 0.0;
  double mean() const { return shadowed ? light / shadowed : 1.0; }
  double share() const { return shadowed ? double(leaking) / shadowed : 1.0; }
};

Scene overlappingCasters() {
  Scene s = shadowtest::testScene();
  s.primitives.resize(1);  // the floor alone
  shadowtest::addBox(s, {0.0f, 0.5f, 0.0f}, {1.0f, 0.5f, 1.0f});    // the large box, on the floor
  shadowtest::addBox(s, {0.5f, 2.5f, -0.8f}, {0.25f, 0.25f, 0.25f});  // the small one, above it
  DirectionalLight d;
  d.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.9f));
  d.intensity = 0.8f;
  s.directionalLights.push_back(d);
  return s;
}

Leak leak(double bleed, const std::string& name) {
  const Scene scene = overlappingCasters();
  ProbeOptions o = evsm();
  o.edit = [bleed](nlohmann::json& doc) {
    for (auto& pass : doc["passes"])
      if (pass["name"] == "lighting" && pass["params"]["shadows"] == true) pass["params"]["evsm_bleed"] = bleed;
  };
  Leak l;
  shadowtest::forEachProbe(scene, scene.directionalLights[0], {LightKind::directional, 0, 0, 4}, o,
                           [&](const ProbeResult& r) {
                             if (r.nearEdge || r.exact != oracle::Visibility::shadowed) return;
                             if (r.probe.point.y > 0.01) return;  // the floor's probes
                             ++l.shadowed;
                             l.light += r.lightLevel;
                             l.worst = std::max(l.worst, r.lightLevel);
                             l.leaking += r.lightLevel > 0.05;
                           },
                           "shadow-" + name);
  std::printf("[ measure  ] %s (evsm_bleed %.2f): %d shadowed floor probes, mean light %.3f%%, worst %.1f%%, "
              "%.3f%% above 5%%\n",
              name.c_str(), bleed, l.shadowed, 100.0 * l.mean(), 100.0 * l.worst, 100.0 * l.share());
  return l;
}

constexpr double kShippedBleed = 0.2;  // pipelines/deferred-pbr-shadows-evsm.json
constexpr double kMaxLeakShare = 0.005;
constexpr double kMaxMeanLight = 0.005;

TEST_F(ShadowEvsm, LightLeakingUnderOverlappingCastersStaysBoundedAtTheShippedBleedReduction) {
  const Leak shipped = leak(kShippedBleed, "evsm-leak");
  EXPECT_GE(shipped.shadowed, 1000);
  EXPECT_LE(shipped.share(), kMaxLeakShare);
  EXPECT_LE(shipped.mean(), kMaxMeanLight);
}

// The same scene without the reduction leaks past the bound: the bound can fail.
TEST_F(ShadowEvsm, WithoutTheBleedReductionTheSameScenesLeaksPastTheBound) {
  const Leak none = leak(0.0, "evsm-leak-no-reduction");
  EXPECT_GE(none.shadowed, 1000);
  EXPECT_GT(none.share(), kMaxLeakShare);
}

// The moments as the pass leaves them, read back: all layers of `level`.
std::vector<float> readLevel(uint32_t texture, int level, glm::ivec3& size) {
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &size.x);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &size.y);
  glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &size.z);
  std::vector<float> texels(size_t(size.x) * size.y * size.z * 4);
  glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
  return texels;
}

struct Moments {
  std::vector<float> level0, level1;
  glm::ivec3 size0{0}, size1{0};
};

// The sun's scene at 256^2 maps and 64^2 moments (blur radius `blur`).
Moments renderMoments(int blur) {
  Scene scene = shadowtest::testScene();
  scene.directionalLights.push_back(shadowtest::sun());
  nlohmann::json doc = shadowtest::pipelineDoc("evsm");
  for (auto& pass : doc["passes"]) {
    if (pass["type"] == "shadow_map") pass["params"]["size"] = 256;
    if (pass["type"] == "shadow_moments") pass["params"].update({{"size", 64}, {"blur", blur}});
  }
  PipelineConfig cfg = testsupport::buildPipelineOrThrow(doc.dump(), "deferred-pbr-shadows-evsm.json (test)");
  const Extent size{96, 64};
  adaptToScene(cfg, PassRegistry::builtins(), sceneFeatures(scene, scene.camera, 1.5f));
  ShaderLibrary shaders;
  Moments m;
  rtest::render(cfg, scene, size, shaders, [&](Executor& exec) {
    const uint32_t texture = exec.textureOf("shadowMoments");
    ASSERT_NE(texture, 0u);
    m.level0 = readLevel(texture, 0, m.size0);
    m.level1 = readLevel(texture, 1, m.size1);
  });
  return m;
}

// |a - b| within 1e-4 of their magnitude: the moments span e^-5 .. e^40.
bool near(double a, double b) { return std::abs(a - b) <= 1e-4 * std::max({std::abs(a), std::abs(b), 1e-30}); }

TEST_F(ShadowEvsm, MomentsAreTheBoxBlurOfTheUnblurredOnesAndEachMipLevelAveragesTheOneAbove) {
  const Moments sharp = renderMoments(0), blurred = renderMoments(2);
  ASSERT_EQ(sharp.size0, glm::ivec3(64, 64, 4));  // the sun's four cascades
  ASSERT_EQ(blurred.size1, glm::ivec3(32, 32, 4));
  const glm::ivec3 s = sharp.size0;
  auto at = [&](const std::vector<float>& v, glm::ivec3 size, int x, int y, int layer, int c) {
    x = std::clamp(x, 0, size.x - 1), y = std::clamp(y, 0, size.y - 1);
    return double(v[((size_t(layer) * size.y + y) * size.x + x) * 4 + c]);
  };
  // Blur: the 5x5 box (clamped at the edges) of the unblurred moments.
  int blurOff = 0, differs = 0;
  double worstBlur = 0.0;
  for (int layer = 0; layer < s.z; ++layer)
    for (int y = 0; y < s.y; ++y)
      for (int x = 0; x < s.x; ++x)
        for (int c = 0; c < 4; ++c) {
          double box = 0.0;
          for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) box += at(sharp.level0, s, x + dx, y + dy, layer, c) / 25.0;
          const double got = at(blurred.level0, s, x, y, layer, c);
          blurOff += !near(got, box);
          differs += !near(got, at(sharp.level0, s, x, y, layer, c));
          worstBlur = std::max(worstBlur, std::abs(got - box) / std::max(std::abs(box), 1e-30));
        }
  // Mips: level 1 is the 2x2 average of level 0.
  int mipOff = 0;
  double worstMip = 0.0;
  const glm::ivec3 s1 = blurred.size1;
  for (int layer = 0; layer < s1.z; ++layer)
    for (int y = 0; y < s1.y; ++y)
      for (int x = 0; x < s1.x; ++x)
        for (int c = 0; c < 4; ++c) {
          double mean = 0.0;
          for (int k = 0; k < 4; ++k) mean += at(blurred.level0, s, 2 * x + (k & 1), 2 * y + (k >> 1), layer, c) / 4.0;
          const double got = at(blurred.level1, s1, x, y, layer, c);
          mipOff += !near(got, mean);
          worstMip = std::max(worstMip, std::abs(got - mean) / std::max(std::abs(mean), 1e-30));
        }
  std::printf("[ measure  ] evsm moments: %d of %d values off the 5x5 box (worst relative %.2e), %d differ from "
              "the unblurred; mip 1: %d off the 2x2 mean (worst relative %.2e)\n",
              blurOff, s.x * s.y * s.z * 4, worstBlur, differs, mipOff, worstMip);
  EXPECT_EQ(blurOff, 0);
  EXPECT_GT(differs, s.x * s.y);  // the blur did something: shadows' edges are in every cascade
  EXPECT_EQ(mipOff, 0);
}

}  // namespace
