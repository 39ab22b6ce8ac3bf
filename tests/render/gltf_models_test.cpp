// Every sample model under ../shared/assets/gltf loads with the scene
// defaults (a camera framing it, a light) and renders through the default
// pipeline into an image that is not just background, with no GL errors, and
// lit: against the ambient-only frame of the same scene and pipeline (lights
// removed), at least kLitOfCovered of the pixels the model covers are
// brighter by kMinLightGain (8/255) or more, so a black frame or one whose
// lights were dropped fails.
// AlphaBlendModeTest's BLEND quads come out blended: between what is behind
// them and the same quad drawn opaque.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "support/render_util.h"
#include "rgraph/scene.h"

#include "rgraph/adapt.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{128, 128};

// The default pipeline as `rgraph render` runs it for this scene.
PipelineConfig defaultPipelineFor(const Scene& scene) {
  PipelineConfig cfg = loadPipeline(repoPath("pipelines/default.json"));
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  return cfg;
}

struct Model {
  const char* file;
  double minCoverage;  // share of pixels that must differ from the background
};


// The default light (a sun from above, behind the camera) reaches nearly all
// the camera sees: measured 78% (Suzanne: 12.4% of the pixels lit of 15.9%
// covered) to 100% (the boxes) of the covered pixels gain 8/255 or more.
constexpr double kLitOfCovered = 0.7;

class GltfModels : public RenderTest, public ::testing::WithParamInterface<Model> {};

}  // namespace

TEST_P(GltfModels, LoadsAndRendersWithoutGlErrors) {
  const Model m = GetParam();
  const std::string path = assetPath(std::string("gltf/") + m.file);
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  Scene scene;
  ASSERT_NO_THROW(scene = loadSceneAny(path));
  ASSERT_GT(scene.primitives.size(), 0u);
  EXPECT_TRUE(scene.hasCamera);
  EXPECT_TRUE(scene.hasPointLights() || scene.hasDirectionalLights());

  const uint64_t errorsBefore = glContext().debugErrorCount();
  const Image img = render(defaultPipelineFor(scene), scene, kSize, *shaders);
  EXPECT_EQ(glContext().debugErrorCount(), errorsBefore) << glContext().lastDebugError();
  const double covered = coverage(img, {0, 0, 0});
  std::printf("[ measure  ] %s: %.1f%% of pixels differ from the background\n", m.file, covered * 100.0);
  EXPECT_GE(covered, m.minCoverage) << m.file << " renders (nearly) empty: " << saveImage(img, "model-empty");
  const Scene unlit = ambientOnly(scene);
  const Image ambient = render(defaultPipelineFor(unlit), unlit, kSize, *shaders);
  const LightGain gain = lightGain(img, ambient, kMinLightGain);
  std::printf("[ measure  ] %s: %s\n", m.file, gain.describe().c_str());
  // (Never less than kLitOfCovered of the model's minimum coverage: a black
  // frame covers nothing and must fail here too.)
  EXPECT_GE(gain.share(), kLitOfCovered * std::max(covered, m.minCoverage))
      << m.file << ": the light does not show: " << gain.describe() << "; images " << saveImage(img, "model-lit")
      << ", " << saveImage(ambient, "model-ambient");
  // Not blown out either: some pixels are below full white.
  size_t white = 0;
  for (size_t i = 0; i + 3 < img.rgba.size(); i += 4)
    white += img.rgba[i] == 255 && img.rgba[i + 1] == 255 && img.rgba[i + 2] == 255;
  EXPECT_LT(static_cast<double>(white) / (img.rgba.size() / 4), 0.5) << m.file << " is mostly white";
}

INSTANTIATE_TEST_SUITE_P(SampleModels, GltfModels,
                         ::testing::Values(Model{"Box/Box.glb", 0.15}, Model{"BoxTextured/BoxTextured.glb", 0.15},
                                           Model{"Cube/Cube.gltf", 0.15},
                                           Model{"MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb", 0.10},
                                           Model{"NormalTangentMirrorTest/NormalTangentMirrorTest.glb", 0.15},
                                           Model{"Suzanne/Suzanne.gltf", 0.10},
                                           Model{"AlphaBlendModeTest/AlphaBlendModeTest.glb", 0.15},
                                           Model{"TextureSettingsTest/TextureSettingsTest.glb", 0.15}),
                         [](const ::testing::TestParamInfo<Model>& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('/'));
                         });

// AlphaBlendModeTest: render it three ways: as is (A), without BLEND
// surfaces (B: what is behind them), and with the BLEND material made opaque
// (C: the surface alone). Where a blended quad covers a pixel, A lies between
// B and C on every channel, and for a good share of those pixels strictly
// between them: the quad is mixed with what is behind, not pasted over it or
// dropped.
TEST_F(RenderTest, AlphaBlendModeTestBlendsItsBlendQuads) {
  const std::string path = assetPath("gltf/AlphaBlendModeTest/AlphaBlendModeTest.glb");
  const Scene scene = loadSceneAny(path);
  ASSERT_TRUE(scene.hasBlendMaterials());

  Scene withoutBlend = scene;
  std::erase_if(withoutBlend.primitives, [&](const Primitive& p) {
    return scene.materials[static_cast<size_t>(p.material)].alphaMode == AlphaMode::blend;
  });
  ASSERT_LT(withoutBlend.primitives.size(), scene.primitives.size());
  Scene opaque = scene;
  for (Material& m : opaque.materials)
    if (m.alphaMode == AlphaMode::blend) m.alphaMode = AlphaMode::opaque;

  // At 256x256 the quads' alpha gradients span enough pixels to measure.
  const Extent size{256, 256};
  const Image a = render(defaultPipelineFor(scene), scene, size, *shaders);
  const Image b = render(defaultPipelineFor(withoutBlend), withoutBlend, size, *shaders);
  const Image c = render(defaultPipelineFor(opaque), opaque, size, *shaders);

  const int tol = 3;  // the opaque copy goes through the rgba8 G-buffer, the blended one is lit forward
  size_t covered = 0, between = 0, strictly = 0;
  std::string firstBad;
  for (int row = 0; row < static_cast<int>(size.height); ++row) {
    for (int x = 0; x < static_cast<int>(size.width); ++x) {
      const glm::ivec3 ca = a.rgb(x, row), cb = b.rgb(x, row), cc = c.rgb(x, row);
      const glm::ivec3 bc = glm::abs(cb - cc);
      // Pixels where the blend surface is visible and differs clearly from what is behind it.
      if (std::max({bc.r, bc.g, bc.b}) < 24) continue;
      ++covered;
      bool ok = true, strict = false;
      for (int i = 0; i < 3; ++i) {
        const int lo = std::min(cb[i], cc[i]), hi = std::max(cb[i], cc[i]);
        if (ca[i] < lo - tol || ca[i] > hi + tol) ok = false;
        if (hi - lo >= 24 && ca[i] > lo + tol && ca[i] < hi - tol) strict = true;
      }
      between += ok;
      strictly += ok && strict;
      if (!ok && firstBad.empty())
        firstBad = "pixel (" + std::to_string(x) + "," + std::to_string(row) + "): blended " + pixelText(ca) +
                   ", behind " + pixelText(cb) + ", opaque " + pixelText(cc);
    }
  }
  std::printf("[ measure  ] AlphaBlendModeTest: %zu pixels covered by BLEND quads, %zu between behind and opaque, "
              "%zu strictly mixed\n",
              covered, between, strictly);
  ASSERT_GT(covered, 500u) << "the BLEND quads cover too few pixels to judge";
  EXPECT_GE(static_cast<double>(between) / covered, 0.98)
      << firstBad << "; images " << saveImage(a, "alphablend-A") << " " << saveImage(b, "alphablend-B-behind") << " "
      << saveImage(c, "alphablend-C-opaque");
  EXPECT_GE(static_cast<double>(strictly) / covered, 0.3) << "too few pixels are a mix of the two";
}
