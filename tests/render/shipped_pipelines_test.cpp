// Shipped pipelines. The LearnOpenGL-style ones (pipelines/*.json: the same
// Blinn-Phong lighting, 5/256 cut-off (none in deferred-blinn-phong.json, as
// in the chapter's 8.1 program), light boxes and tone mapping) render
// the LearnOpenGL scene alike, whatever their method (fullscreen loop, light
// volumes, forward) or G-buffer layout, within what their formats allow.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "support/render_util.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

#include "rgraph/adapt.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{256, 144};

class ShippedPipelines : public RenderTest {};

}  // namespace

TEST_F(ShippedPipelines, LearnOpenGLFamilyAgreesWithForward) {
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig forward = loadPipeline(repoPath("pipelines/forward.json"));
  const Image reference = render(forward, scene, kSize, *shaders);
  EXPECT_GT(coverage(reference, {0, 0, 0}), 0.2);
  expectLightsShow(reference, forward, scene, *shaders, 0.05, "shipped-forward");
  // Each light is cut off at its 5/256 radius: a pixel on that boundary
  // flips between "lit by 5/256 of the light" and "not lit" when its
  // position moves by a hair, a jump of up to ~5/255. The half-float
  // positions of the LearnOpenGL layout (llvmpipe truncates to half: up to
  // 0.002 at |x| = 3) move a few boundary pixels across; forward shading
  // and the compact layout (position from depth) do not. So: within 2/255
  // except on cut-off boundaries (at most 0.1% of the pixels, at most 6/255).
  const size_t maxOver = static_cast<size_t>(kSize.width) * kSize.height / 1000;
  for (const char* pipeline :
       {"default.json", "deferred-light-volumes.json", "deferred-compact.json"}) {
    SCOPED_TRACE(pipeline);
    const Image img = render(loadPipeline(repoPath(std::string("pipelines/") + pipeline)), scene, kSize, *shaders);
    const ImageDiff d = compareImages(reference, img, 2);
    std::printf("[ measure  ] %s vs forward.json (learnopengl scene): %s\n", pipeline, d.describe().c_str());
    EXPECT_LE(d.over, maxOver) << d.describe() << "; " << saveImage(img, std::string("shipped-") + pipeline);
    EXPECT_LE(d.maxDiff, 6) << d.describe() << "; " << saveImage(img, std::string("shipped-") + pipeline);
  }
}

// deferred-blinn-phong.json is LearnOpenGL 8.1: every light at every pixel
// with no cut-off. So it agrees with forward shading at threshold 0 (the
// same maths, no radius anywhere), and the chapter-8.2 radius would change
// the picture far from the lights: a pipeline that cut its lights fails here.
TEST_F(ShippedPipelines, BlinnPhongPipelineShadesEveryLightEverywhereLikeChapter81) {
  const Scene scene = makeLearnOpenGLScene();
  PipelineConfig forward = loadPipeline(repoPath("pipelines/forward.json"));
  setParam(forward, "forward_lit", "threshold", 0.0);
  const Image reference = render(forward, scene, kSize, *shaders);
  EXPECT_GT(coverage(reference, {0, 0, 0}), 0.2);
  expectLightsShow(reference, forward, scene, *shaders, 0.05, "shipped-forward-no-cutoff");

  const PipelineConfig shipped = loadPipeline(repoPath("pipelines/deferred-blinn-phong.json"));
  const Image img = render(shipped, scene, kSize, *shaders);
  // No cut-off ring: only half-float G-buffer positions and normals differ
  // from forward's fp32 varyings, a smooth error of at most 1-2/255.
  const ImageDiff d = compareImages(reference, img, 2);
  std::printf("[ measure  ] deferred-blinn-phong.json vs forward.json at threshold 0: %s\n", d.describe().c_str());
  EXPECT_LE(d.maxDiff, 2) << d.describe() << "; " << saveImage(img, "shipped-deferred-blinn-phong");

  // The same pipeline with the 8.2 radius (5/256) is visibly different.
  PipelineConfig cut = shipped;
  setParam(cut, "lighting", "threshold", 5.0 / 256.0);
  const ImageDiff dc = compareImages(reference, render(cut, scene, kSize, *shaders), 2);
  std::printf("[ measure  ] deferred-blinn-phong.json cut at 5/256 vs no cut-off: %s\n", dc.describe().c_str());
  EXPECT_GE(dc.maxDiff, 20) << dc.describe();
}

// Every shipped pipeline (built-in pass types only) renders the procedural
// scene and glTF models of every kind (one material, MASK and BLEND, normal
// maps, metallic/roughness variation) without GL errors and not empty,
// adapted to each scene as `rgraph render` does. Each frame is checked
// against a reference a wrong image fails: a lit pipeline's frame against the
// ambient-only frame of the same pipeline and scene (lights removed), which
// it must exceed by kMinLightGain on a stated share of pixels (a black frame and
// an ambient-only one fail); the G-buffer debug view (normals shown as
// n * 0.5 + 0.5) must not change with the lights and must decode to unit
// normals on the pixels it covers (black decodes to length 1.73).
namespace {
// Share of the 64x64 pixels that must gain kMinLightGain from the lights, for
// every lit pipeline and scene: measured 12.3% (deferred-pbr.json with
// NormalTangentMirrorTest) to 41.5% (printed as "[ measure  ]"); a black or
// ambient-only frame gains 0%.
constexpr double kMinLitShare = 0.09;

bool showsGBuffer(const PipelineConfig& cfg) {
  return std::any_of(cfg.graph.passes.begin(), cfg.graph.passes.end(),
                     [](const auto& p) { return p.type == "gbuffer_view"; });
}

// Share of pixels whose colour decodes (c / 255 * 2 - 1) to a unit normal
// within what 8 bits allow (one level is 2/255 in n: |n| within 0.03 of 1).
double unitNormalShare(const Image& img) {
  size_t unit = 0;
  for (size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
    const glm::dvec3 n = glm::dvec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]) / 255.0 * 2.0 - 1.0;
    unit += std::abs(glm::length(n) - 1.0) <= 0.03;
  }
  return static_cast<double>(unit) / static_cast<double>(img.rgba.size() / 4);
}
}  // namespace

TEST_F(ShippedPipelines, EveryPipelineRendersEveryKindOfScene) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(repoPath("pipelines")))
    if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 8u);
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("learnopengl", makeLearnOpenGLScene());
  for (const char* m : {"Box/Box.glb", "AlphaBlendModeTest/AlphaBlendModeTest.glb",
                        "NormalTangentMirrorTest/NormalTangentMirrorTest.glb",
                        "MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb"})
    scenes.emplace_back(m, loadSceneAny(assetPath(std::string("gltf/") + m)));
  for (const auto& file : files) {
    Diagnostics diags;
    if (!ConfigDocument::parseFile(file, diags).plugins().empty()) continue;  // needs its plugins (tests/plugin)
    PipelineConfig base;
    try {
      base = loadPipeline(file);
    } catch (const RuntimeError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    for (const auto& [name, scene] : scenes) {
      SCOPED_TRACE(file + " with " + name);
      PipelineConfig cfg = base;
      adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
      const uint64_t errors = glContext().debugErrorCount();
      Image img;
      try {
        img = render(cfg, scene, {64, 64}, *shaders);
      } catch (const RuntimeError& e) {
        ADD_FAILURE() << e.what();
        continue;
      }
      EXPECT_EQ(glContext().debugErrorCount(), errors) << glContext().lastDebugError();
      EXPECT_GT(coverage(img, img.rgb(0, 0)), 0.05) << "empty image " << saveImage(img, "shipped-empty");
      const Scene unlit = ambientOnly(scene);
      PipelineConfig unlitCfg = base;
      adaptToScene(unlitCfg, processRegistry(), sceneFeatures(unlit));
      const Image ambient = render(unlitCfg, unlit, {64, 64}, *shaders);
      const std::string stem = "shipped-" + std::filesystem::path(file).stem().string();
      if (showsGBuffer(cfg)) {
        const ImageDiff same = compareImages(img, ambient, 0);
        EXPECT_EQ(same.maxDiff, 0) << "a G-buffer view changed with the lights: " << same.describe();
        const double unit = unitNormalShare(img);
        std::printf("[ measure  ] %s with %s: %.1f%% of pixels decode to unit normals\n", file.c_str(), name.c_str(),
                    unit * 100.0);
        EXPECT_GE(unit, 0.05) << saveImage(img, stem + "-normals");
        continue;
      }
      const LightGain gain = lightGain(img, ambient, kMinLightGain);
      std::printf("[ measure  ] %s with %s: %s\n", file.c_str(), name.c_str(), gain.describe().c_str());
      EXPECT_GE(gain.share(), kMinLitShare) << "the lights do not show: " << gain.describe() << "; images "
                                            << saveImage(img, stem + "-lit") << ", "
                                            << saveImage(ambient, stem + "-ambient");
    }
  }
}
