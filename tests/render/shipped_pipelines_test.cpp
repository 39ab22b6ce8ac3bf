// Shipped pipelines. The LearnOpenGL-style ones (pipelines/*.json: the same
// Blinn-Phong lighting, 5/256 cut-off (none in deferred-blinn-phong.json, as
// in the chapter's 8.1 program), light boxes and tone mapping) render
// the LearnOpenGL scene alike, whatever their method (fullscreen loop, light
// volumes, forward) or G-buffer layout, within what their formats allow.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "render_util.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

#if __has_include("rgraph/adapt.h")
#include "rgraph/adapt.h"
#define RGRAPH_HAVE_ADAPT 1
#endif

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{256, 144};

class ShippedPipelines : public RenderTest {};

}  // namespace

TEST_F(ShippedPipelines, LearnOpenGLFamilyAgreesWithForward) {
  const Scene scene = makeLearnOpenGLScene();
  const Image reference = render(loadPipeline(repoPath("pipelines/forward.json")), scene, kSize, *shaders);
  EXPECT_GT(coverage(reference, {0, 0, 0}), 0.2);
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
// adapted to each scene as `rgraph render` does.
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
#ifdef RGRAPH_HAVE_ADAPT
      adaptToScene(cfg, PassRegistry::builtins(), sceneFeatures(scene));
#endif
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
    }
  }
}
