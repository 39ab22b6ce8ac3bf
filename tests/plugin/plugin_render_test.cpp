// The bloom and SSAO plugins at work (headless GL, 64x64): loaded through the
// loader into a registry, run by the executor from config text.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

using namespace rgraph;

namespace {

const std::string kTestShaders = std::string(RGRAPH_SOURCE_DIR) + "/tests/plugin/shaders";

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = GlContext::create();
  ctx->makeCurrent();
  return *ctx;
}

class PluginRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    errorsAtStart = context().debugErrorCount();
    std::string error;
    for (const char* name : {"bloom", "ssao"}) ASSERT_NE(loader.load(name, {}, error), nullptr) << error;
  }
  void TearDown() override {
    EXPECT_EQ(context().debugErrorCount(), errorsAtStart) << context().lastDebugError();
  }

  PipelineConfig config(const std::string& json) {
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(json, "test.json", diags);
    PipelineConfig cfg = doc.build(registry, diags);
    for (const auto& d : diags) ADD_FAILURE() << formatDiagnostic(d);
    return cfg;
  }

  // Renders one frame at 64x64 and reads a resource (R of RGBA32F per pixel, rows top-down).
  std::vector<float> render(const PipelineConfig& cfg, const std::string& resource, const Scene* scene = nullptr,
                            int channel = 0) {
    ShaderLibrary shaders;
    shaders.addSearchDirectory(kTestShaders);  // bright_square.frag: names in a config stay inside shader folders
    Executor exec(cfg, registry, shaders, scene);
    exec.resize({64, 64});
    exec.renderFrame();
    std::vector<float> rgba = exec.readTextureRGBA32F(resource);
    std::vector<float> out(rgba.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) out[i] = rgba[i * 4 + channel];
    return out;
  }

  PassRegistry registry = PassRegistry::builtins();  // a copy: built-ins + the plugins
  PluginLoader loader{registry};
  uint64_t errorsAtStart = 0;
};

float at(const std::vector<float>& img, int x, int y) { return img[static_cast<size_t>(y) * 64 + x]; }

std::string bloomConfig(bool inPlace) {
  const std::string composite =
      inPlace ? R"({ "name": "composite", "type": "bloom_composite", "params": { "intensity": 1.0 },
                     "inputs": { "bloom": "blur_a", "color": "hdr" }, "outputs": { "color": "hdr_bloom" } })"
              : R"({ "name": "composite", "type": "bloom_composite", "params": { "intensity": 1.0 },
                     "inputs": { "hdr": "hdr", "bloom": "blur_a" }, "outputs": { "color": "out" } })";
  return R"({
    "version": 1,
    "resources": {
      "hdr":    { "format": "rgba16f" },
      "bright": { "format": "rgba16f", "size": { "scale": 0.5 } },
      "blur_a": { "format": "rgba16f", "size": { "scale": 0.5 } },
      "blur_b": { "format": "rgba16f", "size": { "scale": 0.5 } },
      "out":    { "format": "rgba16f" }
    },
    "passes": [
      { "name": "square", "type": "fullscreen", "params": { "shader": "bright_square.frag" },
        "outputs": { "color": "hdr" } },
      { "name": "bright", "type": "bloom_bright", "params": { "threshold": 1.0, "knee": 0.0 },
        "inputs": { "hdr": "hdr" }, "outputs": { "bright": "bright" } },
      { "name": "blur", "type": "bloom_blur", "params": { "iterations": 3 },
        "inputs": { "src": "bright" }, "outputs": { "dst": "blur_a", "temp": "blur_b" } },
      )" + composite + R"(
    ],
    "output": ")" + (inPlace ? "hdr_bloom" : "out") + R"("
  })";
}

}  // namespace

TEST_F(PluginRenderTest, BloomSpreadsABrightSquare) {
  std::vector<float> img = render(config(bloomConfig(false)), "out");
  ASSERT_EQ(img.size(), 64u * 64u);
  // The square (texels 28..35) keeps its value plus its own glow.
  EXPECT_GE(at(img, 32, 32), 10.0f);
  // Light spreads beyond the square, fading with distance.
  const float near = at(img, 32, 38), mid = at(img, 32, 44), far = at(img, 2, 2);
  EXPECT_GT(near, 0.05f);
  EXPECT_GT(near, mid);
  EXPECT_LT(far, 1e-3f);
  for (float v : img) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
}

TEST_F(PluginRenderTest, BloomCompositeInPlaceMatches) {
  std::vector<float> separate = render(config(bloomConfig(false)), "out");
  std::vector<float> inPlace = render(config(bloomConfig(true)), "hdr_bloom");
  ASSERT_EQ(separate.size(), inPlace.size());
  float maxDiff = 0.0f;
  for (size_t i = 0; i < separate.size(); ++i) maxDiff = std::max(maxDiff, std::abs(separate[i] - inPlace[i]));
  EXPECT_LT(maxDiff, 1e-2f);
}

namespace {
std::string ssaoConfig(const std::string& layout) {
  const bool compact = layout == "compact";
  const std::string resources =
      compact ? R"("gNormal": { "format": "rg16f" }, "gAlbedo": { "format": "rgba8" },
                   "gMaterial": { "format": "rg8" }, "gDepth": { "format": "depth32f" },)"
      : layout == "learnopengl"
          ? R"("gPosition": { "format": "rgba16f" }, "gNormal": { "format": "rgba16f" },
               "gAlbedo": { "format": "rgba8" }, "gDepth": { "format": "depth24_stencil8" },)"
          : R"("gPosition": { "format": "rgba16f" }, "gNormal": { "format": "rgba16f" },
               "gAlbedo": { "format": "rgba16f" }, "gMaterial": { "format": "rgba16f" },
               "gDepth": { "format": "depth32f" },)";
  const std::string gbufferOut =
      compact ? R"("normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial", "depth": "gDepth")"
      : layout == "learnopengl"
          ? R"("position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "depth": "gDepth")"
          : R"("position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial",
               "depth": "gDepth")";
  const std::string ssaoIn = compact ? R"("normal": "gNormal", "depth": "gDepth")"
                                     : R"("position": "gPosition", "normal": "gNormal")";
  return R"({
    "version": 1,
    "resources": { )" + resources + R"(
      "ao_raw": { "format": "r8" }, "ao": { "format": "r16f" } },
    "passes": [
      { "name": "gbuffer", "type": "geometry", "params": { "layout": ")" + layout + R"(" },
        "outputs": { )" + gbufferOut + R"( } },
      { "name": "ssao", "type": "ssao", "params": { "layout": ")" + layout + R"(", "radius": 1.0, "kernel_size": 32, "power": 2.0 },
        "inputs": { )" + ssaoIn + R"( }, "outputs": { "ao": "ao_raw" } },
      { "name": "ssao_blur", "type": "ssao_blur", "inputs": { "src": "ao_raw" }, "outputs": { "ao": "ao" } }
    ],
    "output": "ao"
  })";
}

float mean(const std::vector<float>& v) { return std::accumulate(v.begin(), v.end(), 0.0f) / static_cast<float>(v.size()); }
}  // namespace

TEST_F(PluginRenderTest, SsaoOccludesAndAgreesAcrossGBufferLayouts) {
  // Models standing on a floor: contacts to occlude.
  Scene scene = loadSceneAny(std::string(RGRAPH_SOURCE_DIR) + "/scenes/gltf-models.json");
  std::vector<float> pbr = render(config(ssaoConfig("pbr")), "ao", &scene);
  std::vector<float> compact = render(config(ssaoConfig("compact")), "ao", &scene);
  std::vector<float> learnopengl = render(config(ssaoConfig("learnopengl")), "ao", &scene);
  ASSERT_EQ(pbr.size(), 64u * 64u);
  for (float v : pbr) EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
  // Some corners and contacts are occluded, most of the image is open.
  EXPECT_LT(*std::min_element(pbr.begin(), pbr.end()), 0.75f);
  EXPECT_GT(mean(pbr), 0.5f);
  EXPECT_LT(mean(pbr), 0.999f);
  // Positions rebuilt from depth (compact) give the same occlusion as stored ones.
  float diffCompact = 0.0f, diffLearn = 0.0f;
  for (size_t i = 0; i < pbr.size(); ++i) {
    diffCompact += std::abs(pbr[i] - compact[i]);
    diffLearn += std::abs(pbr[i] - learnopengl[i]);
  }
  std::printf("ao mean: pbr %.4f compact %.4f learnopengl %.4f; min pbr %.3f\n", mean(pbr), mean(compact),
              mean(learnopengl), *std::min_element(pbr.begin(), pbr.end()));
  EXPECT_LT(diffCompact / static_cast<float>(pbr.size()), 0.03f);
  EXPECT_LT(diffLearn / static_cast<float>(pbr.size()), 0.03f);
}

namespace {
// Lighting with an "ao" input cleared to `ao` (or none).
std::string lightingConfig(const std::string& ao) {
  const std::string aoResource = ao.empty() ? "" : R"("occ": { "format": "r8" },)";
  const std::string aoPass = ao.empty() ? "" : R"({ "name": "fill", "type": "clear", "params": { "color": [)" + ao +
                                                   R"(, 0, 0, 1] }, "outputs": { "color": "occ" } },)";
  const std::string aoInput = ao.empty() ? "" : R"(, "ao": "occ")";
  return R"({
    "version": 1,
    "resources": {
      "gPosition": { "format": "rgba16f" }, "gNormal": { "format": "rgba16f" },
      "gAlbedo": { "format": "rgba16f" }, "gMaterial": { "format": "rgba16f" }, "gDepth": { "format": "depth32f" },
      )" + aoResource + R"(
      "hdr": { "format": "rgba16f", "clear": [0, 0, 0, 1] }
    },
    "passes": [
      { "name": "gbuffer", "type": "geometry", "params": { "layout": "pbr" },
        "outputs": { "position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial",
                     "depth": "gDepth" } },
      )" + aoPass + R"(
      { "name": "lighting", "type": "deferred_lighting", "params": { "layout": "pbr", "point_lights": false },
        "inputs": { "position": "gPosition", "normal": "gNormal", "albedo": "gAlbedo", "material": "gMaterial")" +
         aoInput + R"( },
        "outputs": { "color": "hdr" } }
    ],
    "output": "hdr"
  })";
}
}  // namespace

TEST_F(PluginRenderTest, AmbientOcclusionInputScalesOnlyTheAmbientTerm) {
  Scene scene = loadSceneAny("learnopengl");
  const std::vector<float> none = render(config(lightingConfig("")), "hdr", &scene);
  const std::vector<float> open = render(config(lightingConfig("1")), "hdr", &scene);
  const std::vector<float> closed = render(config(lightingConfig("0")), "hdr", &scene);
  float maxOpen = 0.0f, darker = 0.0f;
  bool neverBrighter = true;
  for (size_t i = 0; i < none.size(); ++i) {
    maxOpen = std::max(maxOpen, std::abs(none[i] - open[i]));
    darker = std::max(darker, none[i] - closed[i]);
    if (closed[i] > none[i] + 1e-3f) neverBrighter = false;
  }
  EXPECT_LT(maxOpen, 1e-3f) << "ao = 1 must change nothing";
  EXPECT_GT(darker, 1e-3f) << "ao = 0 must remove the ambient term somewhere";
  EXPECT_TRUE(neverBrighter);
}
