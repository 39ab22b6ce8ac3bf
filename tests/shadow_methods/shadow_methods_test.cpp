// Shadows in every lighting method: the shadows scene (scenes/shadows.json:
// a sun, two spot lights, three shadowed point lights, casters on a floor)
// through each method with 3x3 PCF shadows (tests/shadow_methods/pipelines)
// against the fullscreen deferred_lighting pass with the same shadows. Each
// method must agree with it within the tolerance that method already holds
// unshadowed against deferred_lighting:
//   light_volumes       2/255 per channel (tests/render/light_volumes_test.cpp)
//   tiled_deferred      1e-4 relative in HDR (tests/tiled/tiled_deferred_test.cpp)
//   clustered_deferred  1/255 per channel (tests/render/clustered_test.cpp)
//   forward_lit         2/255 per channel (tests/render/forward_vs_deferred_test.cpp),
//                       also as forward+ (its cluster lists)
// and its shadowed frame must differ from its unshadowed one (the same
// pipeline and scene with nothing casting: the adapt hooks compile the
// shadow code out) on a stated share of pixels, so that two frames that both
// lost their shadows cannot agree. The reference must show its lights
// against its ambient-only frame, so that two black frames cannot agree.
// The blended glass pane is lit by the forward pass (forward_lit's own in
// forward-lit.json), with shadows too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rgraph/adapt.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"
#include "support/test_support.h"

namespace {
using namespace rgraph;
using namespace rgraph::rtest;

constexpr Extent kSize{256, 144};

// Share of pixels the shadows must darken by kMinLightGain (8/255) against
// the same method unshadowed: measured 4.5% for every method (shadows.json at
// 256x144, printed as "[ measure  ]"); a method that lost its shadows darkens 0%.
constexpr double kMinShadowedShare = 0.03;

// Share of pixels the lights must brighten by kMinLightGain against the
// ambient-only frame: measured 71.8%; a black or unlit frame gains 0%.
constexpr double kMinLitShare = 0.3;

std::string pipelinePath(const std::string& name) { return repoPath("tests/shadow_methods/pipelines/" + name); }

// The scene with no primitive casting: every pipeline's shadows adapt away.
Scene withoutCasters(Scene scene) {
  for (Primitive& p : scene.primitives) p.castShadows = false;
  return scene;
}

struct Frame {
  Image image;
  std::vector<float> hdr;
};

// Pixels darker in `shadowed` than in `unshadowed` by kMinLightGain in some channel.
double shadowedShare(const Image& shadowed, const Image& unshadowed) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < shadowed.rgba.size(); i += 4) {
    bool darker = false;
    for (size_t c = 0; c < 3; ++c) darker = darker || unshadowed.rgba[i + c] - shadowed.rgba[i + c] >= kMinLightGain;
    n += darker;
  }
  return static_cast<double>(n) / static_cast<double>(shadowed.rgba.size() / 4);
}

// Worst per-channel difference relative to max(1, |reference|) (the tiled test's measure).
double worstRelative(const std::vector<float>& a, const std::vector<float>& ref) {
  EXPECT_EQ(a.size(), ref.size());
  double worst = 0.0;
  for (size_t i = 0; i < std::min(a.size(), ref.size()); ++i) {
    if (i % 4 == 3) continue;
    const double e = std::abs(double(a[i]) - ref[i]) / std::max(1.0, std::abs(double(ref[i])));
    worst = std::max(worst, std::isfinite(e) ? e : 1e30);
  }
  return worst;
}

struct Method {
  const char* name;
  const char* file;
  const char* hdr;  // the last HDR version (before tone mapping)
  int ldrTolerance;        // per channel, 8-bit; -1: compare HDR
  double hdrTolerance;     // relative
};

class ShadowMethods : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    scene_ = loadSceneAny(repoPath("scenes/shadows.json"));
  }

  Frame renderFrame(const std::string& file, const char* hdr, const Scene& scene, bool expectShadows) {
    return renderFrame(loadPipeline(pipelinePath(file)), file, hdr, scene, expectShadows);
  }
  Frame renderFrame(PipelineConfig cfg, const std::string& file, const char* hdr, const Scene& scene,
                    bool expectShadows) {
    adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
    for (size_t i = 0; i < cfg.graph.passes.size(); ++i)
      if (cfg.graph.passes[i].type != "shadow_map" && cfg.params[i].has("shadows"))
        EXPECT_EQ(cfg.params[i].getBool("shadows"), expectShadows)
            << file << ": pass '" << cfg.graph.passes[i].name << "' after adapting to the scene";
    Frame f;
    f.image = render(cfg, scene, kSize, *shaders, [&](Executor& e) { f.hdr = e.readTextureRGBA32F(hdr); });
    return f;
  }

  const Frame& reference() {
    if (reference_.image.rgba.empty()) {
      reference_ = renderFrame("fullscreen.json", "hdr_forward", scene_, true);
      const Frame ambient = renderFrame("fullscreen.json", "hdr_forward", ambientOnly(scene_), false);
      const LightGain gain = lightGain(reference_.image, ambient.image, kMinLightGain);
      std::printf("[ measure  ] deferred_lighting with shadows vs ambient only: %s\n", gain.describe().c_str());
      EXPECT_GE(gain.share(), kMinLitShare) << "the lights do not show: "
                                            << saveImage(reference_.image, "shadow-methods-fullscreen");
    }
    return reference_;
  }

  void expectAgrees(const Method& m) {
    const Frame& ref = reference();
    const Frame shadowed = renderFrame(m.file, m.hdr, scene_, true);
    const Frame unshadowed = renderFrame(m.file, m.hdr, withoutCasters(scene_), false);
    const double share = shadowedShare(shadowed.image, unshadowed.image);
    const ImageDiff d = compareImages(ref.image, shadowed.image, std::max(m.ldrTolerance, 0));
    const double rel = worstRelative(shadowed.hdr, ref.hdr);
    std::printf("[ measure  ] %s with shadows vs deferred_lighting with shadows: %s; HDR worst relative %.3g; "
                "shadows darken %.1f%% of pixels by %d/255\n",
                m.name, d.describe().c_str(), rel, share * 100.0, kMinLightGain);
    const std::string stem = std::string("shadow-methods-") + m.name;
    EXPECT_GE(share, kMinShadowedShare) << "the shadows do not show: " << saveImage(shadowed.image, stem) << ", "
                                        << saveImage(unshadowed.image, stem + "-unshadowed");
    if (m.ldrTolerance >= 0) {
      EXPECT_EQ(d.over, 0u) << d.describe() << "; " << saveImage(shadowed.image, stem) << ", "
                            << saveImage(ref.image, "shadow-methods-fullscreen");
    } else {
      EXPECT_LE(rel, m.hdrTolerance) << saveImage(shadowed.image, stem) << ", "
                                     << saveImage(ref.image, "shadow-methods-fullscreen");
    }
  }

  Scene scene_;
  Frame reference_;
};

TEST_F(ShadowMethods, ReferenceShadowsShow) {
  const Frame& ref = reference();
  const Frame unshadowed = renderFrame("fullscreen.json", "hdr_forward", withoutCasters(scene_), false);
  const double share = shadowedShare(ref.image, unshadowed.image);
  std::printf("[ measure  ] deferred_lighting: shadows darken %.1f%% of pixels by %d/255\n", share * 100.0,
              kMinLightGain);
  EXPECT_GE(share, kMinShadowedShare) << saveImage(ref.image, "shadow-methods-fullscreen") << ", "
                                      << saveImage(unshadowed.image, "shadow-methods-fullscreen-unshadowed");
}

TEST_F(ShadowMethods, LightVolumesAgreeWithDeferredLighting) {
  expectAgrees({"light_volumes", "light-volumes.json", "hdr_forward", 2, 0.0});
}

TEST_F(ShadowMethods, TiledDeferredAgreesWithDeferredLighting) {
  expectAgrees({"tiled_deferred", "tiled.json", "hdr_forward", -1, 1e-4});
}

TEST_F(ShadowMethods, ClusteredDeferredAgreesWithDeferredLighting) {
  expectAgrees({"clustered_deferred", "clustered.json", "hdr_forward", 1, 0.0});
}

TEST_F(ShadowMethods, ForwardLitAgreesWithDeferredLighting) {
  expectAgrees({"forward_lit", "forward-lit.json", "hdr", 2, 0.0});
}

// Forward+: the cluster lists' shading (include/cluster_shading.glsl, as in
// clustered_deferred) per fragment; forward_lit's tolerance.
TEST_F(ShadowMethods, ForwardPlusAgreesWithDeferredLighting) {
  expectAgrees({"forward_plus", "forward-plus.json", "hdr", 2, 0.0});
}

// `file` with EVSM shadows: the shadow_moments pass (128^2 moments of the
// 512^2 maps, 5x5 blur) and both lighting passes with shadow_filter evsm.
PipelineConfig evsmVariant(const std::string& file) {
  std::ifstream in(pipelinePath(file));
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc = nlohmann::json::parse(text.str());
  doc["resources"]["shadowScratch"] = {{"format", "rgba32f"}, {"size", {16, 16}}, {"layers", 2}};
  doc["resources"]["shadowMoments"] = {{"format", "rgba32f"}, {"size", {16, 16}}, {"layers", 2}, {"mips", "full"}};
  nlohmann::json passes = nlohmann::json::array();
  for (auto& pass : doc["passes"]) {
    if (pass.contains("params") && pass["params"].contains("shadow_filter")) {
      pass["params"]["shadow_filter"] = "evsm";
      pass["inputs"]["shadow_moments"] = "shadowMoments";
    }
    passes.push_back(pass);
    if (pass["type"] == "shadow_map")
      passes.push_back({{"name", "moments"}, {"type", "shadow_moments"}, {"params", {{"size", 128}, {"blur", 2}}},
                        {"inputs", {{"atlas", "shadowAtlas"}, {"info", "shadowInfo"}}},
                        {"outputs", {{"scratch", "shadowScratch"}, {"moments", "shadowMoments"}}}});
  }
  doc["passes"] = passes;
  return testsupport::buildPipelineOrThrow(doc.dump(), file + " (evsm)");
}

// EVSM in deferred_lighting shows its shadows (against the same pipeline with
// nothing casting), and tiled_deferred (the compute path: its mip level from
// the same footprint, no derivatives) agrees with it within tiled's tolerance.
TEST_F(ShadowMethods, EvsmInDeferredLightingShowsAndTiledDeferredAgrees) {
  const Frame ref = renderFrame(evsmVariant("fullscreen.json"), "fullscreen.json", "hdr_forward", scene_, true);
  const Frame unshadowed =
      renderFrame(evsmVariant("fullscreen.json"), "fullscreen.json", "hdr_forward", withoutCasters(scene_), false);
  const double share = shadowedShare(ref.image, unshadowed.image);
  const Frame tiled = renderFrame(evsmVariant("tiled.json"), "tiled.json", "hdr_forward", scene_, true);
  const double rel = worstRelative(tiled.hdr, ref.hdr);
  std::printf("[ measure  ] deferred_lighting evsm: shadows darken %.1f%% of pixels by %d/255; tiled_deferred evsm "
              "vs deferred_lighting evsm: HDR worst relative %.3g\n",
              share * 100.0, kMinLightGain, rel);
  EXPECT_GE(share, kMinShadowedShare) << saveImage(ref.image, "shadow-methods-evsm") << ", "
                                      << saveImage(unshadowed.image, "shadow-methods-evsm-unshadowed");
  EXPECT_LE(rel, 1e-4) << saveImage(tiled.image, "shadow-methods-evsm-tiled") << ", "
                       << saveImage(ref.image, "shadow-methods-evsm");
}

}  // namespace
