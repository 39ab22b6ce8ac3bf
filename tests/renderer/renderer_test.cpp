// The public renderer API (rgraph/renderer.h) in a context the test owns, as
// an embedding program would use it: config errors as diagnostics, per-frame
// camera and light edits without rebuilding, imported textures, several
// renderers sharing one scene upload, rendering into the caller's framebuffer.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "caller_drawing.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/renderer.h"
#include "rgraph/pipeline_load.h"
#include "test_support.h"

namespace {
using namespace rgraph;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";
constexpr Extent kSize{96, 64};

std::unique_ptr<Renderer> makeRenderer(const std::string& path = kDefault, Extent size = kSize) {
  RendererOptions options;
  options.size = size;
  Diagnostics diags;
  auto r = Renderer::fromFile(path, options, diags);
  EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  return r;
}

RendererOptions sized(Extent size) {
  RendererOptions options;
  options.size = size;
  return options;
}

std::vector<uint8_t> renderOnce(Renderer& r) {
  r.render();
  return r.readOutputRGBA8();
}

size_t differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < std::min(a.size(), b.size()); i += 4)
    n += !std::equal(a.begin() + static_cast<std::ptrdiff_t>(i), a.begin() + static_cast<std::ptrdiff_t>(i + 4),
                     b.begin() + static_cast<std::ptrdiff_t>(i));
  return n + (a.size() != b.size() ? 1 : 0);
}

using testsupport::errorOf;  // the message of the RuntimeError a call throws

class RendererApi : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

TEST_F(RendererApi, ConfigErrorsComeBackAsLocatedDiagnosticsNotExceptions) {
  Diagnostics diags;
  auto bad = Renderer::fromJson("{\n  \"version\": 1,\n  \"passes\": [ { \"name\": \"a\", \"type\": \"nope\" } ]\n}",
                                "inline.json", {}, diags);
  EXPECT_FALSE(bad);
  ASSERT_FALSE(diags.empty());
  const auto unknownType = std::find_if(diags.begin(), diags.end(), [](const Diagnostic& d) {
    return d.where.path == "/passes/0/type" && d.message.find("nope") != std::string::npos;
  });
  ASSERT_NE(unknownType, diags.end()) << formatDiagnostic(diags.front());
  EXPECT_EQ(unknownType->where.file, "inline.json");
  EXPECT_EQ(unknownType->where.line, 3);

  diags.clear();
  EXPECT_FALSE(Renderer::fromJson("{ \"version\": 1, ", "broken.json", {}, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().where.file, "broken.json");
  EXPECT_GT(diags.front().where.line, 0);

  diags.clear();
  EXPECT_FALSE(Renderer::fromFile("/no/such/pipeline.json", {}, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_NE(diags.front().message.find("pipeline.json"), std::string::npos) << diags.front().message;
}

TEST_F(RendererApi, RendersWhatTheExecutorRendersForTheAdaptedPipeline) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  const auto viaApi = renderOnce(*r);

  PipelineConfig pipeline = testsupport::loadPipelineOrThrow(kDefault);
  adaptToScene(pipeline, processRegistry(), sceneFeatures(scene->scene()));
  ShaderLibrary shaders;
  Executor direct(pipeline, processRegistry(), shaders, &scene->scene());
  direct.resize(kSize);
  direct.renderFrame();
  EXPECT_EQ(differing(viaApi, direct.readOutputRGBA8()), 0u);
  EXPECT_EQ(r->plan().output, kSize);
  EXPECT_FALSE(r->timings().empty());
  EXPECT_GT(r->plan().naiveBytes, 0u);
}

// The must-show: camera and light changes every frame, no pipeline rebuild,
// no GL object created after the first frame; and the edits do show.
TEST_F(RendererApi, CameraAndLightChangesCreateNoGlObjectsAfterTheFirstFrame) {
  auto scene = RenderScene::load("learnopengl:overview");
  ASSERT_GE(scene->pointLightCount(), 4u);
  auto r = makeRenderer();
  r->setScene(scene);
  auto previous = renderOnce(*r);
  ASSERT_EQ(r->builds(), 1u);
  const int64_t created = gl::createdObjectsTotal();

  for (int frame = 1; frame <= 6; ++frame) {
    Camera c = r->camera();
    c.position = glm::vec3(glm::rotate(glm::mat4(1.0f), 0.15f, glm::vec3(0, 1, 0)) * glm::vec4(c.position, 1.0f));
    r->setCamera(c);
    PointLight moved = scene->pointLight(0);
    moved.position += glm::vec3(0.3f, 0.0f, 0.2f);
    scene->setPointLight(0, moved);
    PointLight recoloured = scene->pointLight(1);
    recoloured.color = glm::vec3(frame % 2, 0.5f, 1.0f - (frame % 2));
    scene->setPointLight(1, recoloured);
    if (frame == 2) scene->addPointLight(PointLight{glm::vec3(0.0f, 1.0f, 1.0f), glm::vec3(4.0f, 0.0f, 0.0f)});
    if (frame == 4) scene->removePointLight(2);
    if (frame == 5) scene->setAmbient(glm::vec3(0.3f));
    auto image = renderOnce(*r);
    EXPECT_GT(differing(image, previous), 50u) << "frame " << frame << " did not change";
    previous = std::move(image);
  }
  EXPECT_EQ(gl::createdObjectsTotal() - created, 0) << "GL objects created by camera and light changes";
  EXPECT_EQ(r->builds(), 1u);

  // The edits reached the GPU exactly: a fresh renderer of a scene built with
  // the final lights and camera draws the same image.
  Scene copy = scene->scene();
  auto fresh = makeRenderer();
  fresh->setScene(RenderScene::fromScene(copy));
  fresh->setCamera(r->camera());
  EXPECT_EQ(differing(renderOnce(*fresh), previous), 0u);
}

TEST_F(RendererApi, LosingTheLastPointLightAdaptsThePipelineAgain) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  r->render();
  const auto lit = std::find_if(r->plan().passes.begin(), r->plan().passes.end(), [](const PlannedPass& p) { return p.name == "light_volumes"; });
  ASSERT_NE(lit, r->plan().passes.end());
  EXPECT_FALSE(lit->culled);
  scene->setPointLights({});
  r->render();
  EXPECT_EQ(r->builds(), 2u);
  const auto after = std::find_if(r->plan().passes.begin(), r->plan().passes.end(), [](const PlannedPass& p) { return p.name == "light_volumes"; });
  ASSERT_NE(after, r->plan().passes.end());
  EXPECT_TRUE(after->culled) << "no point lights: no light volumes";
}

// Shadows: a light edit re-adapts exactly when it changes which lights get
// shadow maps (SceneFeatures::shadowLights), not when a shadowed light moves
// within the view or a light that casts nothing comes or goes.
TEST_F(RendererApi, ChangingTheShadowedLightsAdaptsThePipelineAgain) {
  auto scene = RenderScene::load("learnopengl:shadows");
  auto r = makeRenderer();
  r->setScene(scene);
  r->render();
  ASSERT_EQ(r->builds(), 1u);
  PointLight light = scene->pointLight(0);
  light.position = glm::vec3(0.0f, 0.5f, 0.0f);
  light.castShadows = true;
  scene->setPointLight(0, light);
  r->render();
  EXPECT_EQ(r->builds(), 2u) << "a point light now casts";
  light.position = glm::vec3(0.5f, 0.5f, 0.5f);
  scene->setPointLight(0, light);
  scene->addPointLight(PointLight{glm::vec3(0.0f, 1.0f, 1.0f), glm::vec3(1.0f)});
  r->render();
  EXPECT_EQ(r->builds(), 2u) << "moved within the view, and a light that does not cast added";
  light.position = r->camera().position - 50.0f * r->camera().forward();  // far behind the camera
  scene->setPointLight(0, light);
  r->render();
  EXPECT_EQ(r->builds(), 3u) << "the shadowed light left the view";
}

// The tables the last adaptation reported (a shadow template's budget, which rgraph view shows): none
// before a scene, the budget of the shadows scene, none again once nothing in the scene casts.
TEST_F(RendererApi, AdaptTablesAreTheLastAdaptationsReports) {
  auto r = makeRenderer(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr-shadows.json");
  EXPECT_TRUE(r->adaptTables().empty()) << "no scene: nothing adapted";
  r->setScene(RenderScene::load(std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json"));
  r->render();
  ASSERT_EQ(r->adaptTables().size(), 1u);
  const AdaptReport::Table& t = r->adaptTables()[0];
  EXPECT_EQ(t.pass, "shadows");
  // docs/shadows.md "The shadow budget": 6 lights in 24 layers of 2048^2, 4 bytes a texel.
  EXPECT_NE(std::find(t.lines.begin(), t.lines.end(), "atlas: 24 of 24 layers used, 402653184 bytes"), t.lines.end());
  r->setScene(RenderScene::load("learnopengl:overview"));  // 32 point lights, none casting
  r->render();
  EXPECT_TRUE(r->adaptTables().empty());
  EXPECT_FALSE(r->adaptNotes().empty()) << "the notes say why there are no maps";
}

TEST_F(RendererApi, BadLightsAndCamerasAreRefusedAndChangeNothing) {
  auto scene = RenderScene::load("learnopengl:overview");
  PointLight bad = scene->pointLight(0);
  bad.color = glm::vec3(std::numeric_limits<float>::quiet_NaN());
  const uint64_t version = scene->lightsVersion();
  EXPECT_THROW(scene->setPointLight(0, bad), RuntimeError);
  EXPECT_THROW(scene->addPointLight(bad), RuntimeError);
  EXPECT_THROW(scene->setPointLight(scene->pointLightCount(), scene->pointLight(0)), RuntimeError);
  EXPECT_THROW(scene->removePointLight(scene->pointLightCount()), RuntimeError);
  EXPECT_EQ(scene->lightsVersion(), version);
  auto r = makeRenderer();
  Camera c;
  c.position = glm::vec3(std::numeric_limits<float>::infinity());
  EXPECT_THROW(r->setCamera(c), RuntimeError);
}

// Several renderers in one context share one upload of the scene.
TEST_F(RendererApi, TwoRenderersShareOneSceneUploadAndRenderCorrectlyInAlternation) {
  auto shared = RenderScene::load("learnopengl:overview");
  auto main = makeRenderer(kDefault, {96, 64});
  auto inset = makeRenderer(kDefault, {48, 32});
  main->setScene(shared);
  inset->setScene(shared);
  Camera insetCamera = shared->scene().camera;
  insetCamera.position = glm::vec3(4.0f, 6.0f, 4.0f);
  inset->setCamera(insetCamera);

  // References: each alone, with its own upload of the scene.
  auto aloneMain = makeRenderer(kDefault, {96, 64});
  aloneMain->setScene(RenderScene::load("learnopengl:overview"));
  const auto mainRef = renderOnce(*aloneMain);
  auto aloneInset = makeRenderer(kDefault, {48, 32});
  auto ownScene = RenderScene::load("learnopengl:overview");
  aloneInset->setScene(ownScene);
  aloneInset->setCamera(insetCamera);
  const int64_t buffersBefore = gl::createdObjects(gl::ObjectKind::buffer);
  const auto insetRef = renderOnce(*aloneInset);
  const int64_t buffersWithOwnUpload = gl::createdObjects(gl::ObjectKind::buffer) - buffersBefore;
  ASSERT_NE(differing(mainRef, std::vector<uint8_t>(mainRef.size(), 0)), 0u);

  main->render();  // uploads the shared scene
  const int64_t before = gl::createdObjects(gl::ObjectKind::buffer);
  inset->render();  // reuses it: the default pipeline declares no buffer of its own
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::buffer) - before, 0);
  EXPECT_EQ(shared->uploadCount(), 1u);
  // Uploading the scene (2 per mesh, light volume and marker meshes, Frame
  // block, light buffers) is what the renderer with its own scene paid.
  EXPECT_GE(buffersWithOwnUpload, 2 * static_cast<int64_t>(shared->scene().meshes.size() + 2) + 2);
  EXPECT_EQ(ownScene->uploadCount(), 1u);

  for (int round = 0; round < 3; ++round) {
    main->render();
    EXPECT_EQ(differing(main->readOutputRGBA8(), mainRef), 0u) << "round " << round;
    inset->render();
    EXPECT_EQ(differing(inset->readOutputRGBA8(), insetRef), 0u) << "round " << round;
  }
  EXPECT_EQ(shared->uploadCount(), 1u);
}

// ---------------------------------------------------------------- imports

std::string importingPipeline() {
  return R"({
  "version": 1,
  "resources": {
    "tint":   { "format": "rgba16f", "size": "output", "imported": true },
    "output": { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "tonemap", "type": "tonemap", "params": { "operator": "none", "gamma": 1.0 },
      "inputs": { "hdr": "tint" }, "outputs": { "output": "output" } }
  ],
  "output": "output"
})";
}

gl::Texture makeTexture(Format f, Extent e, uint32_t samples = 1) { return gl::createTexture2D(f, e, 1, samples); }

TEST_F(RendererApi, ImportedTextureIsReadInPlaceAndTheOutputWrittenIntoTheCallers) {
  Diagnostics diags;
  auto r = Renderer::fromJson(importingPipeline(), "import.json", sized({8, 4}), diags);
  ASSERT_TRUE(r) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_EQ(r->importableResources(), (std::vector<std::string>{"tint", "output"}));
  gl::Texture tint = makeTexture(Format::rgba16f, {8, 4});
  const float colour[4] = {0.25f, 0.5f, 1.0f, 1.0f};
  glClearTexImage(tint.id(), 0, GL_RGBA, GL_FLOAT, colour);
  gl::Texture out = makeTexture(Format::rgba8, {8, 4});
  r->importTexture("tint", tint.id());
  r->importTexture("output", out.id());
  r->render();
  EXPECT_EQ(r->outputTexture(), out.id());
  std::vector<uint8_t> px(8 * 4 * 4);
  glGetTextureImage(out.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(px.size()), px.data());
  EXPECT_EQ(px[0], 64);
  EXPECT_EQ(px[1], 128);
  EXPECT_EQ(px[2], 255);
}

TEST_F(RendererApi, ImportedTextureMismatchIsRefusedNamingTheResourceAndBothDescriptions) {
  Diagnostics diags;
  auto r = Renderer::fromJson(importingPipeline(), "import.json", sized({8, 4}), diags);
  ASSERT_TRUE(r);
  gl::Texture good = makeTexture(Format::rgba16f, {8, 4});
  r->importTexture("tint", good.id());
  r->render();  // built: later imports are checked at once
  auto message = [&](uint32_t texture, const std::string& name = "tint") {
    return errorOf([&] { r->importTexture(name, texture); });
  };
  gl::Texture wrongSize = makeTexture(Format::rgba16f, {16, 4});
  EXPECT_EQ(message(wrongSize.id()),
            "imported texture " + std::to_string(wrongSize.id()) +
                " for resource 'tint' does not match its declaration: the resource is rgba16f 8x4, 1 sample; the "
                "texture is rgba16f 16x4, 1 sample");
  gl::Texture wrongFormat = makeTexture(Format::rgba8, {8, 4});
  EXPECT_NE(message(wrongFormat.id()).find("the resource is rgba16f 8x4, 1 sample; the texture is rgba8 8x4"),
            std::string::npos);
  gl::Texture multisampled = makeTexture(Format::rgba16f, {8, 4}, 4);
  EXPECT_NE(message(multisampled.id()).find("wrong target"), std::string::npos);
  EXPECT_NE(message(987654).find("is not a texture name"), std::string::npos);
  EXPECT_NE(message(good.id(), "tnit").find("no such resource (did you mean 'tint'?)"), std::string::npos);
  // The failed imports changed nothing: the good texture is still in use.
  r->render();
  EXPECT_EQ(r->executor()->textureOf("tint"), good.id());

  // A resource the graph owns (it may alias it) cannot be imported.
  Diagnostics d2;
  auto def = Renderer::fromFile(kDefault, sized({8, 4}), d2);
  ASSERT_TRUE(def);
  gl::Texture hdr = makeTexture(Format::rgba16f, {8, 4});
  const std::string owned = errorOf([&] { def->importTexture("hdr", hdr.id()); });
  EXPECT_NE(owned.find("resource 'hdr': it is not declared \"imported\": true"), std::string::npos) << owned;
}

TEST_F(RendererApi, ImportedTextureOfTheOldSizeIsRefusedAfterResize) {
  Diagnostics diags;
  auto r = Renderer::fromJson(importingPipeline(), "import.json", sized({8, 4}), diags);
  ASSERT_TRUE(r);
  gl::Texture tint = makeTexture(Format::rgba16f, {8, 4});
  r->importTexture("tint", tint.id());
  r->render();
  r->setSize({16, 8});
  const std::string stale = errorOf([&] { r->render(); });
  EXPECT_NE(stale.find("resource 'tint' does not match"), std::string::npos) << stale;
  EXPECT_NE(stale.find("the resource is rgba16f 16x8"), std::string::npos) << stale;
  gl::Texture bigger = makeTexture(Format::rgba16f, {16, 8});
  r->importTexture("tint", bigger.id());
  EXPECT_NO_THROW(r->render());

  // The documented order: setSize, then import textures of the new size.
  r->setSize({12, 6});
  gl::Texture resized = makeTexture(Format::rgba16f, {12, 6});
  EXPECT_NO_THROW(r->importTexture("tint", resized.id()));
  EXPECT_NO_THROW(r->render());
  EXPECT_EQ(r->executor()->textureOf("tint"), resized.id());
  EXPECT_EQ(r->outputExtent(), (Extent{12, 6}));
}

TEST_F(RendererApi, ImportBeforeTheFirstFrameIsCheckedAtOnce) {
  Diagnostics diags;
  auto r = Renderer::fromJson(importingPipeline(), "import.json", sized({8, 4}), diags);
  ASSERT_TRUE(r);
  gl::Texture wrong = makeTexture(Format::rgba16f, {4, 4});
  const std::string early = errorOf([&] { r->importTexture("tint", wrong.id()); });
  EXPECT_NE(early.find("the resource is rgba16f 8x4, 1 sample; the texture is rgba16f 4x4"), std::string::npos)
      << early;
  EXPECT_EQ(r->builds(), 0u) << "checking builds nothing";
}

// ---------------------------------------------------------------- the caller's GL

TEST_F(RendererApi, CallersDrawingAfterAFrameIsUnaffected) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  r->render();  // first frame (builds) outside, so both kinds of frame are covered below
  testsupport::CallerDrawing caller;
  const auto alone = caller.drawAround({});
  std::string first;
  EXPECT_EQ(testsupport::differingPixels(alone, caller.drawAround([&] { r->render(); }), caller.size(), &first), 0u)
      << first;
  // Into another framebuffer of the caller's: a blit, with its own state.
  gl::Texture elsewhere = makeTexture(Format::rgba8, {32, 32});
  gl::Framebuffer elsewhereFbo = gl::createFramebuffer();
  glNamedFramebufferTexture(elsewhereFbo.id(), GL_COLOR_ATTACHMENT0, elsewhere.id(), 0);
  EXPECT_EQ(testsupport::differingPixels(
                alone, caller.drawAround([&] { r->render(elsewhereFbo.id(), {4, 4, 16, 16}); }), caller.size(), &first),
            0u)
      << first;
  r->setSize({48, 32});  // a rebuild inside the frame
  EXPECT_EQ(testsupport::differingPixels(alone, caller.drawAround([&] { r->render(); }), caller.size(), &first), 0u)
      << first;
}

// State a caller may leave set that would change rgraph's own frame is reset
// for the frame and comes back afterwards; a program the caller deleted while
// current causes no GL error.
TEST_F(RendererApi, CallerStateLeftBehindNeitherChangesTheFrameNorIsLost) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  const auto clean = renderOnce(*r);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glPixelStorei(GL_PACK_ROW_LENGTH, 7);
  gl::Program doomed = gl::createProgram();
  {
    gl::Shader vs = gl::createShader(GL_VERTEX_SHADER);
    const char* src = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    glShaderSource(vs.id(), 1, &src, nullptr);
    glCompileShader(vs.id());
    glAttachShader(doomed.id(), vs.id());
    glLinkProgram(doomed.id());
  }
  glUseProgram(doomed.id());
  doomed.reset();  // deleted while current: it lives until unbound
  const uint64_t errors = testsupport::sharedGlContext().debugErrorCount();
  r->render();
  const auto withCallerState = r->readOutputRGBA8();
  GLint mode[2] = {0, 0}, rowLength = 0;
  glGetIntegerv(GL_POLYGON_MODE, mode);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &rowLength);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  EXPECT_EQ(differing(withCallerState, clean), 0u);
  EXPECT_EQ(mode[0], GL_LINE);
  EXPECT_EQ(rowLength, 7);
  EXPECT_EQ(testsupport::sharedGlContext().debugErrorCount(), errors)
      << testsupport::sharedGlContext().lastDebugError();
}

TEST_F(RendererApi, RenderIntoAFramebufferCopiesTheStoredOutputIntoTheViewport) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  gl::Texture target = makeTexture(Format::rgba8, {128, 96});
  const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
  glClearTexImage(target.id(), 0, GL_RGBA, GL_FLOAT, grey);
  gl::Framebuffer fbo = gl::createFramebuffer();
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
  r->render(fbo.id(), Viewport{10, 20, kSize.width, kSize.height});
  const auto expected = r->readOutputRGBA8();  // rows top-down
  std::vector<uint8_t> px(128 * 96 * 4);
  glGetTextureImage(target.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(px.size()), px.data());
  size_t wrong = 0;
  for (uint32_t y = 0; y < 96; ++y)
    for (uint32_t x = 0; x < 128; ++x) {
      const uint8_t* got = &px[(y * 128 + x) * 4];
      const bool inside = x >= 10 && x < 10 + kSize.width && y >= 20 && y < 20 + kSize.height;
      if (inside) {
        const uint32_t row = kSize.height - 1 - (y - 20);  // bottom-up -> top-down
        wrong += !std::equal(got, got + 4, &expected[(row * kSize.width + (x - 10)) * 4]);
      } else {
        wrong += got[0] != 128 || got[1] != 128 || got[2] != 128;
      }
    }
  EXPECT_EQ(wrong, 0u);
}

// Reload: errors keep the last good pipeline; unchanged programs are reused.
TEST_F(RendererApi, ReloadKeepsTheLastGoodPipelineOnErrorsAndReusesPrograms) {
  Diagnostics diags;
  auto r = Renderer::fromJson(importingPipeline(), "reload.json", sized({8, 4}), diags);
  ASSERT_TRUE(r);
  gl::Texture tint = makeTexture(Format::rgba16f, {8, 4});
  const float colour[4] = {0.5f, 0.5f, 0.5f, 1.0f};
  glClearTexImage(tint.id(), 0, GL_RGBA, GL_FLOAT, colour);
  r->importTexture("tint", tint.id());
  const auto before = renderOnce(*r);

  diags.clear();
  std::string broken = importingPipeline();
  broken.replace(broken.find("\"tonemap\", \"params\""), 9, "\"tonemapp\"");
  EXPECT_FALSE(r->reloadJson(broken, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_NE(diags.front().message.find("tonemapp"), std::string::npos) << diags.front().message;
  EXPECT_EQ(differing(renderOnce(*r), before), 0u) << "the last good pipeline keeps rendering";

  // Same programs, another gamma uniform: nothing recompiled.
  std::string gamma = importingPipeline();
  gamma.replace(gamma.find("\"gamma\": 1.0"), 12, "\"gamma\": 2.2");
  diags.clear();
  const int64_t programs = gl::createdObjects(gl::ObjectKind::program);
  ASSERT_TRUE(r->reloadJson(gamma, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  const auto after = renderOnce(*r);
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::program) - programs, 0);
  EXPECT_GT(after[0], before[0]) << "gamma 2.2 brightens mid grey";
  EXPECT_EQ(r->builds(), 2u);
}

}  // namespace

namespace {

// Live reload of shader files: a copy of tonemap.frag in a folder searched
// first, edited while the renderer runs.
class RendererShaderReload : public RendererApi {
 protected:
  void SetUp() override {
    RendererApi::SetUp();
    dir_ = std::filesystem::temp_directory_path() / ("rgraph-reload-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    original_ = readText(std::string(RGRAPH_SOURCE_DIR) + "/shaders/tonemap.frag");
    write(original_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);  // later tests find the built-in tonemap.frag again
  }
  static std::string readText(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  void write(const std::string& text) {
    const auto file = dir_ / "tonemap.frag";
    const auto before = std::filesystem::exists(file) ? std::filesystem::last_write_time(file)
                                                      : std::filesystem::file_time_type::min();
    std::ofstream(file) << text;
    // Coarse file-system clocks: make the edit visible as a change.
    std::filesystem::last_write_time(file, std::max(before + std::chrono::seconds(1),
                                                    std::filesystem::last_write_time(file)));
  }
  std::unique_ptr<Renderer> make(bool checks) {
    RendererOptions options;
    options.size = {8, 4};
    options.runChecks = checks;
    options.shaderDirectories = {dir_.string()};
    Diagnostics diags;
    auto r = Renderer::fromJson(importingPipeline(), "reload.json", options, diags);
    EXPECT_TRUE(r);
    tint_ = makeTexture(Format::rgba16f, {8, 4});
    const float colour[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(tint_.id(), 0, GL_RGBA, GL_FLOAT, colour);
    r->importTexture("tint", tint_.id());
    return r;
  }
  std::filesystem::path dir_;
  std::string original_;
  gl::Texture tint_;
};

TEST_F(RendererShaderReload, AnEditedShaderIsCompiledAgainAndABrokenOneKeepsTheLastGood) {
  auto r = make(/*checks=*/true);
  const auto before = renderOnce(*r);
  const auto watched = r->watchedFiles();
  EXPECT_NE(std::find(watched.begin(), watched.end(), (dir_ / "tonemap.frag").string()), watched.end())
      << "the shader copy is watched";

  // Valid edit: the output halved.
  std::string brighter = original_;
  const size_t end = brighter.rfind('}');
  ASSERT_NE(end, std::string::npos);
  brighter.insert(end, "  outColor.rgb = outColor.rgb * 0.5;\n");
  write(brighter);
  Diagnostics diags;
  const int64_t programs = gl::createdObjects(gl::ObjectKind::program);
  ASSERT_TRUE(r->reload(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::program) - programs, 1) << "only the edited program is rebuilt";
  const auto edited = renderOnce(*r);
  EXPECT_LT(edited[0], before[0]);

  // Broken edit: refused by the shader checks, the edited pipeline keeps running.
  write(original_ + "\nthis is not glsl\n");
  diags.clear();
  EXPECT_FALSE(r->reload(diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().code, DiagCode::shader_error) << formatDiagnostic(diags.front());
  EXPECT_EQ(differing(renderOnce(*r), edited), 0u);

  // Fixed again: recovered.
  write(original_);
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_EQ(differing(renderOnce(*r), before), 0u);
}

TEST_F(RendererShaderReload, WhatOnlyTheDeviceRefusesIsADeviceErrorAndTheLastGoodKeepsRunning) {
  auto r = make(/*checks=*/false);  // no glslang: the driver is the first to see the shader
  const auto before = renderOnce(*r);
  write(original_ + "\nthis is not glsl\n");
  Diagnostics diags;
  const uint64_t builds = r->builds();
  EXPECT_FALSE(r->reload(diags));
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags.front().code, DiagCode::device_error);
  EXPECT_NE(diags.front().message.find("tonemap.frag"), std::string::npos) << diags.front().message;
  EXPECT_EQ(r->builds(), builds);
  EXPECT_EQ(differing(renderOnce(*r), before), 0u) << "the last good pipeline still renders";
  write(original_);
  diags.clear();
  EXPECT_TRUE(r->reload(diags));
  EXPECT_EQ(differing(renderOnce(*r), before), 0u);
}

}  // namespace

namespace {

std::string fileText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A reload builds the pipeline again but keeps what did not change: programs
// (ShaderLibrary) and textures of the same description (Executor::reuseTextures).
TEST_F(RendererApi, ReloadReusesTexturesAndProgramsThatDidNotChange) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  const auto before = renderOnce(*r);
  std::string text = fileText(kDefault);
  const size_t gamma = text.find("\"gamma\": 1.0");
  ASSERT_NE(gamma, std::string::npos);
  text.replace(gamma, 12, "\"gamma\": 2.2");
  Diagnostics diags;
  const int64_t textures = gl::createdObjects(gl::ObjectKind::texture);
  const int64_t programs = gl::createdObjects(gl::ObjectKind::program);
  ASSERT_TRUE(r->reloadJson(text, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::texture) - textures, 0) << "every texture kept its description";
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::program) - programs, 0);
  const auto after = renderOnce(*r);
  EXPECT_GT(differing(after, before), 100u) << "the new gamma shows";

  // One resource changes format: exactly one texture is made; the frame is
  // that of a renderer made from the new text directly.
  const size_t hdr = text.find("\"hdr\":          { \"format\": \"rgba16f\"");
  ASSERT_NE(hdr, std::string::npos);
  text.replace(text.find("rgba16f", hdr), 7, "rgba32f");
  diags.clear();
  const int64_t textures2 = gl::createdObjects(gl::ObjectKind::texture);
  ASSERT_TRUE(r->reloadJson(text, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::texture) - textures2, 1);
  Diagnostics d2;
  auto fresh = Renderer::fromJson(text, "fresh.json", sized(kSize), d2);
  ASSERT_TRUE(fresh);
  fresh->setScene(scene);
  EXPECT_EQ(differing(renderOnce(*r), renderOnce(*fresh)), 0u);
}

}  // namespace

namespace {

// The viewer's "profile" toggle: with CPU timing, passes are timed (a
// glFinish after each) only while it is on; the image never depends on it.
TEST_F(RendererApi, CpuPassTimingCanBeTurnedOffWithoutChangingTheFrame) {
  auto scene = RenderScene::load("learnopengl:overview");
  auto r = makeRenderer();
  r->setScene(scene);
  const auto timed = renderOnce(*r);
  if (!r->cpuTimed()) {  // a GPU with timer queries: the toggle changes nothing
    r->setCpuPassTiming(false);
    EXPECT_EQ(differing(renderOnce(*r), timed), 0u);
    return;
  }
  auto sum = [&] {
    double total = 0.0;
    for (const auto& t : r->timings()) total += t.ms;
    return total;
  };
  EXPECT_GT(sum(), 0.0);
  r->setCpuPassTiming(false);
  EXPECT_EQ(differing(renderOnce(*r), timed), 0u);
  EXPECT_EQ(sum(), 0.0) << "no pass timed while profiling is off";
  r->setCpuPassTiming(true);
  r->setSize({48, 32});  // kept across a rebuild
  r->setCpuPassTiming(false);
  r->render();
  EXPECT_EQ(sum(), 0.0);
  EXPECT_FALSE(r->cpuPassTiming());
}

}  // namespace
