// The embedding API under misuse (issue 25): a scene or renderer drawn in
// another GL context, calls from inside a render() callback, imported textures
// deleted or redefined after importTexture, lights and cameras outside the
// scene files' ranges, the state after a failed call, and the light buffers a
// dragged threshold leaves behind.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";

RendererOptions sized(Extent size) {
  RendererOptions options;
  options.size = size;
  return options;
}

std::unique_ptr<Renderer> fromJson(const std::string& json, Extent size, bool checks = true) {
  RendererOptions options = sized(size);
  options.runChecks = checks;
  Diagnostics diags;
  auto r = Renderer::fromJson(json, "misuse.json", options, diags);
  EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  return r;
}

std::unique_ptr<Renderer> fromFile(const std::string& path, Extent size) {
  Diagnostics diags;
  auto r = Renderer::fromFile(path, sized(size), diags);
  EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  return r;
}

using testsupport::errorOf;  // the message of the RuntimeError a call throws

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

// tint (imported, rgba16f) tone mapped into the output.
std::string importingPipeline(const std::string& tintSize = "\"output\"", const std::string& outSize = "\"output\"") {
  return R"({"version": 1,
  "resources": {"tint": {"format": "rgba16f", "size": )" +
         tintSize + R"(, "imported": true}, "output": {"format": "rgba8", "size": )" + outSize + R"(}},
  "passes": [{"name": "tonemap", "type": "tonemap", "params": {"operator": "none", "gamma": 1.0},
              "inputs": {"hdr": "tint"}, "outputs": {"output": "output"}}],
  "output": "output"})";
}

// Passes the checks (no texture limit is given) but not the device: llvmpipe
// and every current GPU refuse a texture 65536 texels wide.
std::string pipelineTheDeviceRefuses() { return importingPipeline("[65536, 1]", "[65536, 1]"); }

class RendererMisuse : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext().makeCurrent(); }
};

// ---------------------------------------------------------------- contexts

TEST_F(RendererMisuse, ASceneOrRendererDrawnInAnotherContextIsRefusedNotCrashed) {
  GlContext& first = testsupport::sharedGlContext();
  auto scene = RenderScene::load("learnopengl:overview");
  auto main = fromFile(kDefault, {32, 24});
  main->setScene(scene);
  main->render();
  const std::vector<uint8_t> before = main->readOutputRGBA8();
  ASSERT_EQ(scene->uploadCount(), 1u);
  {
    std::unique_ptr<GlContext> second = GlContext::create();  // current now; shares nothing with `first`
    auto other = fromFile(kDefault, {32, 24});
    other->setScene(scene);
    const std::string sceneError = errorOf([&] { other->render(); });
    EXPECT_HAS(sceneError, "RenderScene::gpu: the scene 'learnopengl:overview' was uploaded to the GPU in another GL context");
    // The renderer whose objects live in the first context.
    const std::string rendererError = errorOf([&] { main->render(); });
    EXPECT_HAS(rendererError, "the current GL context is not the one this pipeline's GL objects were made in");
    EXPECT_EQ(second->debugErrorCount(), 0u) << "nothing was drawn with the first context's names: "
                                             << second->lastDebugError();
    other.reset();  // made nothing in this context
  }
  first.makeCurrent();
  main->render();
  EXPECT_EQ(main->readOutputRGBA8(), before) << "the first context still draws as before";
  EXPECT_EQ(scene->uploadCount(), 1u);
}

// ---------------------------------------------------------------- re-entry

TEST_F(RendererMisuse, CallsFromInsideARenderCallbackAreRefusedAndTheFrameFinishes) {
  auto r = fromJson(importingPipeline(), {8, 4});
  gl::Texture tint = gl::createTexture2D(Format::rgba16f, {8, 4}, 1, 1);
  const float colour[4] = {0.25f, 0.5f, 1.0f, 1.0f};
  glClearTexImage(tint.id(), 0, GL_RGBA, GL_FLOAT, colour);
  r->importTexture("tint", tint.id());
  r->render();
  const std::vector<uint8_t> before = r->readOutputRGBA8();
  const uint64_t builds = r->builds();
  auto scene = RenderScene::load("learnopengl");

  std::vector<std::pair<std::string, std::function<void()>>> calls = {
      {"reloadJson", [&] { Diagnostics d; r->reloadJson(importingPipeline(), d); }},
      {"reload", [&] { Diagnostics d; r->reload(d); }},
      {"setSize", [&] { r->setSize({16, 8}); }},
      {"setScene", [&] { r->setScene(scene); }},
      {"setCamera", [&] { r->setCamera(Camera{}); }},
      {"cameraCut", [&] { r->cameraCut(); }},
      {"importTexture", [&] { r->importTexture("tint", tint.id()); }},
      {"releaseTexture", [&] { r->releaseTexture("tint"); }},
      {"setCpuPassTiming", [&] { r->setCpuPassTiming(false); }},
      {"collectTimings", [&] { r->collectTimings(); }},
      {"setAfterPass", [&] { r->setAfterPass({}); }},
      {"render", [&] { r->render(); }},
      {"render", [&] { r->render(0); }},
  };
  std::vector<std::string> messages;
  std::vector<float> readBack;
  r->setAfterPass([&](size_t) {
    for (const auto& [name, call] : calls) messages.push_back(name + ": " + errorOf(call));
    readBack = r->readResourceRGBA32F("output");  // reading is what the callback is for
  });
  r->render();
  ASSERT_EQ(messages.size(), calls.size());
  for (size_t i = 0; i < calls.size(); ++i)
    EXPECT_HAS(messages[i], calls[i].first + ": Renderer::" + calls[i].first +
                                " called from inside a render() callback (setAfterPass)");
  EXPECT_EQ(readBack.size(), 8u * 4u * 4u);
  // Nothing changed: same size, scene, pipeline objects, output.
  EXPECT_EQ(r->size(), (Extent{8, 4}));
  EXPECT_EQ(r->scene(), nullptr);
  EXPECT_EQ(r->builds(), builds);
  EXPECT_EQ(r->readOutputRGBA8(), before);

  // After render() returns, the same calls work; an exception out of the
  // callback ends the frame without leaving the renderer "inside" one.
  r->setAfterPass([](size_t) { throw RuntimeError("callback failed"); });
  EXPECT_EQ(errorOf([&] { r->render(); }), "callback failed");
  r->setAfterPass({});
  Diagnostics d;
  EXPECT_TRUE(r->reloadJson(importingPipeline(), d));
  r->setSize({16, 8});
  gl::Texture bigger = gl::createTexture2D(Format::rgba16f, {16, 8}, 1, 1);
  r->importTexture("tint", bigger.id());
  EXPECT_NO_THROW(r->render());
}

// ---------------------------------------------------------------- imports

TEST_F(RendererMisuse, AnImportedTextureDeletedOrRedefinedAfterImportMakesRenderThrow) {
  auto r = fromJson(importingPipeline(), {8, 4});
  GLuint tint = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tint);
  // No storage yet: refused as such (not "GL internal format 0x1908 0x0").
  EXPECT_EQ(errorOf([&] { r->importTexture("tint", tint); }),
            "imported texture " + std::to_string(tint) +
                " for resource 'tint' has no storage (glTexStorage* never called); the resource is rgba16f 8x4, 1 sample");
  glDeleteTextures(1, &tint);

  // A mutable texture (glTexImage2D) can be redefined in place.
  glGenTextures(1, &tint);
  glBindTexture(GL_TEXTURE_2D, tint);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, 8, 4, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  r->importTexture("tint", tint);
  EXPECT_NO_THROW(r->render());
  glBindTexture(GL_TEXTURE_2D, tint);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, 4, 4, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, 0);
  const std::string redefined = errorOf([&] { r->render(); });
  EXPECT_HAS(redefined, "resource 'tint' does not match its declaration: the resource is rgba16f 8x4, 1 sample; "
                        "the texture is rgba16f 4x4, 1 sample");
  EXPECT_HAS(redefined, "deleted or redefined since importTexture?");

  glDeleteTextures(1, &tint);
  const std::string deleted = errorOf([&] { r->render(); });
  EXPECT_HAS(deleted, "imported texture " + std::to_string(tint) +
                          " for resource 'tint' is not a texture name in the current GL context");

  // A good texture again: rendering resumes.
  gl::Texture good = gl::createTexture2D(Format::rgba16f, {8, 4}, 1, 1);
  r->importTexture("tint", good.id());
  EXPECT_NO_THROW(r->render());
}

// ---------------------------------------------------------------- ranges

TEST_F(RendererMisuse, CamerasOutsideTheSceneFileRangesAreRefused) {
  auto r = fromFile(kDefault, {8, 4});
  const Camera good = r->camera();
  auto refused = [&](const std::function<void(Camera&)>& edit) {
    Camera c = good;
    edit(c);
    return errorOf([&] { r->setCamera(c); });
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(refused([](Camera& c) { c.fovY = -5.0f; }),
            "Renderer::setCamera: camera fov: must be in (0, 180) degrees, got -5");
  EXPECT_HAS(refused([](Camera& c) { c.fovY = 180.0f; }), "camera fov: must be in (0, 180) degrees, got 180");
  EXPECT_HAS(refused([](Camera& c) { c.near = 0.0f; }), "camera near: must be > 0, got 0");
  EXPECT_HAS(refused([](Camera& c) { c.near = -1.0f; }), "camera near: must be > 0, got -1");
  EXPECT_HAS(refused([](Camera& c) { c.far = c.near; }), "camera far: must be greater than near (0.1), got 0.1");
  EXPECT_HAS(refused([&](Camera& c) { c.position.x = nan; }), "camera position: (nan, 0, 5) is not a finite number");
  EXPECT_HAS(refused([](Camera& c) { c.target.y = 1e16f; }), "exceeds +-1e+15 units");
  EXPECT_HAS(refused([](Camera& c) { c.target = c.position; }), "camera target: must differ from the position");
  EXPECT_EQ(r->camera().fovY, good.fovY) << "refused cameras change nothing";
}

TEST_F(RendererMisuse, LightsAndAmbientOutsideTheSceneFileRangesAreRefused) {
  auto scene = RenderScene::load("learnopengl");
  const PointLight good = scene->pointLight(0);
  const uint64_t version = scene->lightsVersion();
  auto point = [&](const std::function<void(PointLight&)>& edit) {
    PointLight l = good;
    edit(l);
    return errorOf([&] { scene->setPointLight(0, l); });
  };
  EXPECT_HAS(point([](PointLight& l) { l.radius = -1.0f; }), "learnopengl: point light 0: radius: must be >= 0, got -1");
  EXPECT_HAS(point([](PointLight& l) { l.intensity = -2.0f; }), "point light 0: intensity: must be >= 0, got -2");
  EXPECT_HAS(point([](PointLight& l) { l.color = glm::vec3(1, -1, 1); }), "point light 0: color: values must be >= 0");
  EXPECT_HAS(point([](PointLight& l) { l.linear = -0.5f; }), "point light 0: linear: must be >= 0, got -0.5");
  EXPECT_HAS(point([](PointLight& l) { l.constant = l.linear = l.quadratic = 0.0f; }),
             "constant, linear and quadratic cannot all be 0");
  EXPECT_HAS(point([](PointLight& l) { l.position.z = std::numeric_limits<float>::quiet_NaN(); }),
             "point light 0: position: (2.4, 0.86, nan) is not a finite number");
  EXPECT_HAS(errorOf([&] { scene->setAmbient(glm::vec3(-5.0f)); }),
             "learnopengl: ambient: values must be >= 0, got (-5, -5, -5)");
  DirectionalLight zero;
  zero.direction = glm::vec3(0.0f);
  EXPECT_HAS(errorOf([&] { scene->setDirectionalLights({zero}); }),
             "directional light 0: direction: must not be the zero vector");
  DirectionalLight dim;
  dim.intensity = -1.0f;
  EXPECT_HAS(errorOf([&] { scene->setDirectionalLights({dim}); }), "directional light 0: intensity: must be >= 0");
  EXPECT_EQ(scene->lightsVersion(), version) << "refused edits change nothing";
  // A NaN light built in code is reported the same way when the scene is made.
  Scene s = makeLearnOpenGLScene();
  s.pointLights[1].position.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_HAS(errorOf([&] { RenderScene::fromScene(s); }), "point light 1: position: (nan,");
  EXPECT_HAS(errorOf([&] { RenderScene::fromScene(s); }), "is not a finite number");
}

// ---------------------------------------------------------------- failed calls

// A reload the device refuses (after setSize, setScene or an import made a
// rebuild pending) leaves that rebuild pending: the next frame is built for
// the new size and scene with the last good pipeline, as size() says.
TEST_F(RendererMisuse, AFailedReloadKeepsWhatEarlierCallsAskedFor) {
  auto r = fromJson(importingPipeline(), {8, 4});
  gl::Texture small = gl::createTexture2D(Format::rgba16f, {8, 4}, 1, 1);
  r->importTexture("tint", small.id());
  r->render();

  r->setSize({16, 8});
  gl::Texture bigger = gl::createTexture2D(Format::rgba16f, {16, 8}, 1, 1);
  r->importTexture("tint", bigger.id());
  Diagnostics diags;
  EXPECT_FALSE(r->reloadJson(pipelineTheDeviceRefuses(), diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.back().code, DiagCode::device_error);  // after a warning: its size is not the output's
  EXPECT_EQ(r->size(), (Extent{16, 8}));
  r->render();
  EXPECT_EQ(r->outputExtent(), (Extent{16, 8})) << "the frame after the failed reload is at size()";
  EXPECT_EQ(r->executor()->textureOf("tint"), bigger.id()) << "and uses the texture imported for it";

  // The same with a scene: the frame draws the scene scene() returns.
  auto def = fromFile(kDefault, {8, 4});
  auto one = RenderScene::load("learnopengl");
  auto two = RenderScene::load("thin");
  def->setScene(one);
  def->render();
  def->setScene(two);
  diags.clear();
  EXPECT_FALSE(def->reloadJson(pipelineTheDeviceRefuses(), diags));
  def->render();
  EXPECT_EQ(&def->executor()->gpuScene()->scene(), &two->scene());
  EXPECT_EQ(two->uploadCount(), 1u);
}

// ---------------------------------------------------------------- light buffers

// Each threshold value had its own light buffer, kept for the scene's
// lifetime: 100 values (a slider dragged, viewer `param` edits, both through
// reloadJson) left 100 buffers. The cache now holds the last few.
TEST_F(RendererMisuse, DistinctLightVolumeThresholdsLeaveTheGlObjectCountSteady) {
  const std::string path = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-light-volumes.json";
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string key = "\"threshold\": 0.01953125";
  ASSERT_NE(text.find(key), std::string::npos);
  auto withThreshold = [&](double t) {
    std::string s = text;
    s.replace(s.find(key), key.size(), "\"threshold\": " + std::to_string(t));
    return s;
  };
  auto r = fromJson(text, {16, 12}, /*checks=*/false);
  r->setScene(RenderScene::load("many-lights:32"));
  r->render();
  int64_t steady = 0;
  for (int i = 0; i < 100; ++i) {
    Diagnostics diags;
    ASSERT_TRUE(r->reloadJson(withThreshold(0.002 + 0.0005 * i), diags)) << formatDiagnostic(diags.front());
    r->render();
    if (i == 10) steady = gl::liveObjectsTotal();
  }
  EXPECT_EQ(gl::liveObjectsTotal(), steady) << "GL objects after 100 distinct thresholds vs after 10";
}

}  // namespace

namespace {

// The program issue 25 ran under valgrind (docs/testing.md has the command):
// a renderer from a file, three frames, a reload, one more frame.
TEST_F(RendererMisuse, FromFileThreeFramesAndReload) {
  auto r = fromFile(kDefault, {32, 24});
  r->setScene(RenderScene::load("learnopengl:overview"));
  for (int frame = 0; frame < 3; ++frame) r->render();
  const std::vector<uint8_t> before = r->readOutputRGBA8();
  Diagnostics diags;
  ASSERT_TRUE(r->reload(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  r->render();
  EXPECT_EQ(r->readOutputRGBA8(), before);
}

}  // namespace
