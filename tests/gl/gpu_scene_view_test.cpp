// GpuScene's draws from a caller's view (drawView, drawLayered, drawEachLayer):
// the same view gives the same pixels into a plain 2D texture, a layer of a 2D
// array and a face of a cube map; one layered draw gives what one draw per
// layer gives; the camera's Frame block is untouched by them (bytes, binding,
// and a later pass of the executor renders as it did without them). Every
// comparison is exact (rgba32f, max diff 0).
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_util.h"
#include "layered_target.h"
#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr uint32_t kSide = 48;  // square: cube map faces are
constexpr int kArrayLayers = 3;

// A colour and a depth texture of kSide texels a side (layered_target.h).
struct Target : LayeredTarget {
  Target(GLenum t, int n) : LayeredTarget(t, kSide, n) {}
};

// Pixels where a and b differ (bit for bit), and how many pixels a surface covers.
size_t differing(const Pixels& a, const Pixels& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(glm::vec4)) != 0;
  return n;
}
size_t covered(const Pixels& a) {
  return static_cast<size_t>(std::count_if(a.begin(), a.end(), [](const glm::vec4& p) { return p.w != 0.0f; }));
}

Camera sideCamera() {
  Camera c;
  c.position = {6.0f, 4.0f, -5.0f};
  c.target = {0.0f, 0.5f, 0.0f};
  return c;
}

GpuScene::View viewOf(const Camera& c, float aspect = 1.0f) {
  GpuScene::View v;
  v.view = c.view();
  v.proj = c.projection(aspect);
  v.eye = c.position;
  return v;
}

// The six cube-map face views from `eye` (GL's face order +X -X +Y -Y +Z -Z,
// with the usual cube-map up vectors), 90 degrees each.
std::vector<GpuScene::View> cubeViews(glm::vec3 eye) {
  const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  std::vector<GpuScene::View> views;
  for (int f = 0; f < 6; ++f) {
    GpuScene::View v;
    v.view = glm::lookAt(eye, eye + dirs[f], ups[f]);
    v.proj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 50.0f);
    v.cull = GpuScene::Cull::none;  // a cube map seen from inside flips winding: draw both sides
    views.push_back(v);
  }
  return views;
}

struct GpuSceneViewTest : GlTest {
  Scene scene = loadSceneAny("learnopengl:overview");
  std::unique_ptr<GpuScene> gpu;
  uint32_t probe = 0, terms = 0, layered = 0;
  void SetUp() override {
    GlTest::SetUp();
    gpu = std::make_unique<GpuScene>(scene);
    gpu->updateFrame({kSide, kSide});
    probe = shaders->program("scene.vert", "view_probe.frag");
    terms = shaders->program("scene.vert", "view_probe.frag", {"FRAME_TERMS"});
    if (gpu->supportsLayeredDraw()) layered = shaders->program("scene.vert", "view_probe.frag", {"LAYERED"});
  }
  void TearDown() override {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    gpu.reset();
    GlTest::TearDown();
  }
  // drawPrimitives (the camera's block) or drawView into a plain 2D target.
  Pixels drawCamera(uint32_t program) {
    Target t(GL_TEXTURE_2D, 1);
    glEnable(GL_DEPTH_TEST);
    gpu->drawPrimitives(program, {});
    return t.read(0);
  }
  Pixels draw2D(uint32_t program, const GpuScene::View& v) {
    Target t(GL_TEXTURE_2D, 1);
    glEnable(GL_DEPTH_TEST);
    gpu->drawView(program, v);
    return t.read(0);
  }
};

// A view given as matrices draws what the camera's Frame block draws for a
// camera with those matrices: same positions, same depth, and the view's own
// u_cameraPos and u_viewport (FRAME_TERMS reads them).
TEST_F(GpuSceneViewTest, AViewDrawsWhatTheFrameBlockOfTheSameCameraDraws) {
  const Camera side = sideCamera();
  gpu->updateFrame({kSide, kSide}, side);
  const Pixels viaFrame = drawCamera(probe), termsViaFrame = drawCamera(terms);
  gpu->updateFrame({kSide, kSide});  // back to the scene's camera
  const Pixels camera = drawCamera(probe);
  const Pixels viaView = draw2D(probe, viewOf(side)), termsViaView = draw2D(terms, viewOf(side));
  ASSERT_GT(covered(viaView), 100u);
  EXPECT_EQ(differing(viaView, viaFrame), 0u);
  EXPECT_EQ(differing(termsViaView, termsViaFrame), 0u);
  EXPECT_GT(differing(viaView, camera), 100u);  // the side view is not the camera's
}

// The same view into layer k of a 2D array and face f of a cube map gives
// the 2D texture's pixels; the other layers stay cleared.
TEST_F(GpuSceneViewTest, AViewIntoAnArrayLayerOrACubeFaceEqualsThePlain2DRender) {
  const GpuScene::View v = viewOf(sideCamera());
  const Pixels plain = draw2D(probe, v);
  ASSERT_GT(covered(plain), 100u);
  Target array(GL_TEXTURE_2D_ARRAY, kArrayLayers);
  glEnable(GL_DEPTH_TEST);
  array.attachLayer(2);
  gpu->drawView(probe, v);
  EXPECT_EQ(differing(array.read(2), plain), 0u);
  EXPECT_EQ(covered(array.read(0)), 0u);
  EXPECT_EQ(covered(array.read(1)), 0u);
  Target cube(GL_TEXTURE_CUBE_MAP, 6);
  for (int face : {0, 3, 5}) {
    cube.attachLayer(face);
    gpu->drawView(probe, v);
    EXPECT_EQ(differing(cube.read(face), plain), 0u) << "face " << face;
  }
  EXPECT_EQ(covered(cube.read(1)), 0u);
}

// One instanced draw per primitive writing every layer through gl_Layer
// gives exactly what one draw per layer gives, for array layers (three
// different views) and the six faces of a cube map.
TEST_F(GpuSceneViewTest, OneLayeredDrawEqualsOneDrawPerLayer) {
  if (!gpu->supportsLayeredDraw()) GTEST_SKIP() << "no gl_Layer from the vertex shader on this device";
  Camera a = sideCamera(), b = sideCamera(), c = sideCamera();
  b.position = {-5.0f, 6.0f, 4.0f};
  c.position = {0.5f, 2.0f, 8.0f};
  struct Case {
    const char* name;
    GLenum target;
    std::vector<GpuScene::View> views;
  };
  const Case cases[] = {{"array", GL_TEXTURE_2D_ARRAY, {viewOf(a), viewOf(b), viewOf(c)}},
                        {"cube", GL_TEXTURE_CUBE_MAP, cubeViews({0.0f, 1.5f, 0.0f})}};
  for (const Case& k : cases) {
    Target perLayer(k.target, int(k.views.size()));
    glEnable(GL_DEPTH_TEST);
    gpu->drawEachLayer(probe, k.views, [&](size_t i) { perLayer.attachLayer(int(i)); });
    Target oneDraw(k.target, int(k.views.size()));
    oneDraw.attachAll();
    gpu->drawLayered(layered, k.views);
    size_t coveredLayers = 0;
    for (size_t i = 0; i < k.views.size(); ++i) {
      const Pixels expected = perLayer.read(int(i));
      coveredLayers += covered(expected) > 0;
      EXPECT_EQ(differing(oneDraw.read(int(i)), expected), 0u) << k.name << " layer " << i;
      if (i > 0) {
        EXPECT_GT(differing(expected, perLayer.read(int(i) - 1)), 0u) << k.name << " layer " << i;
      }
    }
    EXPECT_GE(coveredLayers, k.views.size() - 1) << k.name;  // the scene shows in (nearly) every direction
  }
}

// firstLayer offsets every view's layer: views 0 and 1 land in layers 1 and 2.
TEST_F(GpuSceneViewTest, LayeredDrawStartsAtFirstLayer) {
  if (!gpu->supportsLayeredDraw()) GTEST_SKIP() << "no gl_Layer from the vertex shader on this device";
  const GpuScene::View v = viewOf(sideCamera());
  const Pixels plain = draw2D(probe, v);
  Target array(GL_TEXTURE_2D_ARRAY, kArrayLayers);
  glEnable(GL_DEPTH_TEST);
  gpu->drawLayered(layered, {v, v}, 1);
  EXPECT_EQ(covered(array.read(0)), 0u);
  EXPECT_EQ(differing(array.read(1), plain), 0u);
  EXPECT_EQ(differing(array.read(2), plain), 0u);
}

TEST_F(GpuSceneViewTest, LayeredDrawRefusesViewsThatOneDrawCannotCover) {
  if (!gpu->supportsLayeredDraw()) GTEST_SKIP() << "no gl_Layer from the vertex shader on this device";
  GpuScene::View a = viewOf(sideCamera()), b = a;
  b.cull = GpuScene::Cull::front;
  try {
    gpu->drawLayered(layered, {a, b});
    FAIL() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("every view must have the first one's viewport, cull, filter"),
              std::string::npos)
        << e.what();
  }
}

// Drawing from another view leaves the camera's Frame block as it was: its
// bytes, its binding at uniform buffer 0 (and the scene's record of it), and
// what a later camera draw renders.
TEST_F(GpuSceneViewTest, TheCameraBlockIsUntouchedByAView) {
  const Pixels before = drawCamera(probe);
  const uint32_t block = gpu->recordedFrameBinding();
  ASSERT_NE(block, 0u);
  std::vector<uint8_t> bytesBefore(576), bytesAfter(576);
  glGetNamedBufferSubData(block, 0, 576, bytesBefore.data());
  draw2D(probe, viewOf(sideCamera()));
  if (gpu->supportsLayeredDraw()) {
    Target cube(GL_TEXTURE_CUBE_MAP, 6);
    gpu->drawLayered(layered, cubeViews({0, 1, 0}));
  }
  glGetNamedBufferSubData(block, 0, 576, bytesAfter.data());
  EXPECT_EQ(bytesBefore, bytesAfter);
  EXPECT_EQ(gpu->recordedFrameBinding(), block);
  GLint bound = 0;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &bound);
  EXPECT_EQ(uint32_t(bound), block);
  EXPECT_EQ(differing(drawCamera(probe), before), 0u);
}

// Filters: shadowCasters leaves out a primitive whose castShadows is false
// (and blended ones); the counts follow.
TEST_F(GpuSceneViewTest, ShadowCastersFilterLeavesOutNonCasters) {
  ASSERT_GE(scene.primitives.size(), 2u);
  const GpuScene::View v = viewOf(sideCamera());
  const Pixels all = draw2D(probe, v);
  const size_t opaque = gpu->primitiveCount(GpuScene::Filter::opaque);
  EXPECT_EQ(gpu->primitiveCount(GpuScene::Filter::shadowCasters), opaque);
  scene.primitives[0].castShadows = false;  // the GpuScene reads the Scene it was made from
  EXPECT_EQ(gpu->primitiveCount(GpuScene::Filter::shadowCasters), opaque - 1);
  GpuScene::View casters = v;
  casters.filter = GpuScene::Filter::shadowCasters;
  const Pixels some = draw2D(probe, casters);
  EXPECT_GT(differing(all, some), 0u);
  EXPECT_LT(covered(some), covered(all));
  GpuScene::View blend = v;
  blend.filter = GpuScene::Filter::blend;  // this scene has no blended material
  EXPECT_EQ(covered(draw2D(probe, blend)), 0u);
}

// Cull modes: culling front faces shows the far side of closed meshes (never
// nearer than the near side back culling shows); none shows the nearest.
TEST_F(GpuSceneViewTest, CullModesPickTheFacesDrawn) {
  GpuScene::View v = viewOf(sideCamera());
  const Pixels back = draw2D(probe, v);
  v.cull = GpuScene::Cull::front;
  const Pixels front = draw2D(probe, v);
  v.cull = GpuScene::Cull::none;
  const Pixels none = draw2D(probe, v);
  size_t farther = 0, nearer = 0;
  for (size_t i = 0; i < back.size(); ++i) {
    if (back[i].w == 0.0f || front[i].w == 0.0f) continue;
    farther += front[i].w > back[i].w;
    nearer += front[i].w < back[i].w;
  }
  EXPECT_GT(farther, 100u);
  EXPECT_EQ(nearer, 0u);
  EXPECT_EQ(differing(none, back), 0u);  // depth-tested: the nearest faces are the front faces
}

// A view's viewport is set for its draw: nothing lands outside it, and the
// block's u_viewport is its size.
TEST_F(GpuSceneViewTest, AViewportLimitsTheDraw) {
  GpuScene::View v = viewOf(sideCamera());
  v.viewport = GpuScene::Viewport{8, 16, 24, 24};
  const Pixels px = draw2D(terms, v);
  size_t outside = 0, inside = 0;
  for (uint32_t y = 0; y < kSide; ++y)
    for (uint32_t x = 0; x < kSide; ++x) {
      const glm::vec4& p = px[y * kSide + x];
      const bool in = x >= 8 && x < 32 && y >= 16 && y < 40;
      if (p.w == 0.0f) continue;
      (in ? inside : outside)++;
      if (in) {
        EXPECT_NEAR(p.y, (x + 0.5f) / 24.0f, 1e-6f) << x << "," << y;  // gl_FragCoord.x / u_viewport.x
      }
    }
  EXPECT_GT(inside, 50u);
  EXPECT_EQ(outside, 0u);
}

// ---------------------------------------------------------------- in a pipeline

// Draws the scene from the side view into its own target, as a shadow or
// reflection pass would, binding through the executor's record.
struct SideViewPass final : PassInstance {
  uint32_t program = 0;
  void setup(PassContext& ctx) override { program = ctx.program(0); }
  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glEnable(GL_DEPTH_TEST);
    ctx.gpuScene()->drawView(program, viewOf(sideCamera()));
    glDisable(GL_DEPTH_TEST);
  }
  uint32_t changedState() const override { return 0; }
};

// The default pipeline renders the same image with a pass before its
// geometry pass that draws the scene from another view; the state checks
// (bindings, the Frame block's record) find nothing wrong with that pass.
TEST_F(GpuSceneViewTest, APassDrawingAnotherViewLeavesLaterPassesUnchanged) {
  PassRegistry reg = PassRegistry::builtins();
  PassTypeDesc d;
  d.name = "side_view";
  d.description = "test: the scene from the side";
  d.slots.resize(1);
  d.slots[0].name = "color";
  d.slots[0].access = Access::color_attachment;
  d.programs = [](const ParamSet&) { return std::vector<ShaderProgramSpec>{programSpec("scene.vert", "view_probe.frag")}; };
  d.create = [] { return std::make_unique<SideViewPass>(); };
  ASSERT_TRUE(reg.add(d));
  const PipelineConfig plain = loadPipelineFileOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json");
  PipelineConfig withView = plain;
  ResourceDecl side;
  side.name = "side";
  side.texture.format = Format::rgba32f;
  withView.graph.resources.push_back(side);
  PassDecl p;
  p.name = "side";
  p.type = "side_view";
  p.uses = {writeUse("color", Access::color_attachment, "side")};
  p.sideEffect = true;
  withView.graph.passes.insert(withView.graph.passes.begin(), p);
  withView.params.insert(withView.params.begin(), ParamSet{});
  auto render = [&](const PipelineConfig& cfg) {
    Executor exec(cfg, reg, *shaders, &scene);
    exec.setStateChecks(true);
    exec.resize({96, 64});
    exec.renderFrame();
    return exec.readOutputRGBA8();
  };
  const std::vector<uint8_t> expected = render(plain);
  std::vector<uint8_t> got;
  ASSERT_NO_THROW(got = render(withView));
  EXPECT_EQ(got, expected);
}

}  // namespace
