// EXT_mesh_gpu_instancing in GpuScene: a primitive with N instance matrices
// is one instanced draw that gives exactly the pixels of N primitives placed
// by hand (world position and depth, rgba32f, max diff 0), from the camera,
// from another view and through a layered draw (shadow maps: GL instance =
// instance * views + view), where every layer shows every instance.
#include <GL/glcorearb.h>

#include <cstdio>
#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_test_util.h"
#include "layered_target.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/scene.h"
#include "support/cube_scene.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr uint32_t kSide = 64;

// Three instances of a cube under a node transform.
std::vector<glm::mat4> instanceMatrices() {
  std::vector<glm::mat4> m;
  m.push_back(glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, 0.0f, 0.0f)));
  m.push_back(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, -1.0f)), 0.6f, glm::vec3(0, 1, 0)));
  m.push_back(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.0f, 0.5f)), glm::vec3(0.5f, 1.5f, 0.5f)));
  return m;
}

// The node's own transform: identity, so that both scenes compute each world
// position with the same float operations (node * instance is tested on the
// CPU: tests/scene/gltf_geometry_features_test.cpp).
const glm::mat4 kNode(1.0f);

// instanced: one primitive with the instances; else one primitive per instance (transform = node * instance).
Scene instancedScene(bool instanced) {
  Scene s = testsupport::singleMeshScene(makeCube(0.5f));
  Primitive p = s.primitives[0];
  s.primitives.clear();
  if (instanced) {
    p.transform = kNode;
    p.instances = instanceMatrices();
    p.bounds = p.worldBounds(s.meshes[0].bounds);
    s.primitives.push_back(p);
  } else {
    for (const glm::mat4& m : instanceMatrices()) {
      p.transform = kNode * m;
      p.bounds = p.worldBounds(s.meshes[0].bounds);
      s.primitives.push_back(p);
    }
  }
  testsupport::lookAtOrigin(s, {1.0f, 2.5f, 6.0f});
  return s;
}

// An rgba32f array of `n` layers with depth, attached whole (layered) or one layer (layered_target.h).
struct Target : LayeredTarget {
  explicit Target(int n) : LayeredTarget(GL_TEXTURE_2D_ARRAY, kSide, n) {}
};

size_t differing(const Pixels& a, const Pixels& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}
size_t covered(const Pixels& a) {
  size_t n = 0;
  for (const glm::vec4& p : a) n += p != glm::vec4(0.0f);
  return n;
}

GpuScene::View viewFrom(glm::vec3 eye) {
  GpuScene::View v;
  v.view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  v.proj = glm::perspective(glm::radians(50.0f), 1.0f, 0.1f, 30.0f);
  v.eye = eye;
  return v;
}

struct GpuSceneInstancing : GlTest {
  Scene instanced = instancedScene(true), expanded = instancedScene(false);
  std::unique_ptr<GpuScene> gi, ge;
  void SetUp() override {
    GlTest::SetUp();
    glEnable(GL_DEPTH_TEST);  // every draw of these tests
    gi = std::make_unique<GpuScene>(instanced);
    ge = std::make_unique<GpuScene>(expanded);
  }
  void TearDown() override {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    gi.reset();
    ge.reset();
    GlTest::TearDown();
  }
};

}  // namespace

TEST_F(GpuSceneInstancing, OneInstancedDrawEqualsOnePrimitivePerInstance) {
  const uint32_t probe = shaders->program("scene.vert", "view_probe.frag");
  // The scenes' bounds agree: those of the instanced primitive cover every instance.
  EXPECT_EQ(instanced.bounds().min, expanded.bounds().min);
  EXPECT_EQ(instanced.bounds().max, expanded.bounds().max);
  EXPECT_EQ(gi->primitiveCount(GpuScene::Filter::opaque), 1u);  // one draw
  Target a(1), b(1);
  gi->updateFrame({kSide, kSide});
  a.bindAndClear();
  gi->drawPrimitives(probe, {});
  const Pixels viaInstances = a.read(0);
  ge->updateFrame({kSide, kSide});
  b.bindAndClear();
  ge->drawPrimitives(probe, {});
  const Pixels viaPrimitives = b.read(0);
  std::printf("[ measure  ] 3 instances cover %zu of %u pixels\n", covered(viaInstances), kSide * kSide);
  EXPECT_GT(covered(viaPrimitives), kSide * kSide / 10);
  EXPECT_EQ(differing(viaInstances, viaPrimitives), 0u);
  // And from another view (drawView: shadow maps' one-view path).
  a.bindAndClear();
  gi->drawView(probe, viewFrom({-4.0f, 3.0f, 2.0f}));
  b.bindAndClear();
  ge->drawView(probe, viewFrom({-4.0f, 3.0f, 2.0f}));
  EXPECT_GT(covered(b.read(0)), kSide * kSide / 10);
  EXPECT_EQ(differing(a.read(0), b.read(0)), 0u);
}

// drawLayered (point-light and cascade shadow maps): every layer of the one
// instanced draw holds every instance, as one draw per layer of the expanded
// scene does.
TEST_F(GpuSceneInstancing, ALayeredDrawShowsEveryInstanceInEveryLayer) {
  if (!gi->supportsLayeredDraw()) GTEST_SKIP() << "no gl_Layer from the vertex shader on this device";
  const uint32_t probe = shaders->program("scene.vert", "view_probe.frag");
  const uint32_t layered = shaders->program("scene.vert", "view_probe.frag", {"LAYERED"});
  const std::vector<GpuScene::View> views = {viewFrom({-4.0f, 3.0f, 2.0f}), viewFrom({0.0f, 6.0f, 0.5f}),
                                             viewFrom({5.0f, 1.0f, -3.0f})};
  gi->updateFrame({kSide, kSide});
  ge->updateFrame({kSide, kSide});
  Target oneDraw(3), perLayer(3);
  oneDraw.bindAndClear();
  gi->drawLayered(layered, views);
  ge->drawEachLayer(probe, views, [&](size_t i) { perLayer.attachLayer(int(i)); });
  for (int i = 0; i < 3; ++i) {
    const Pixels expected = perLayer.read(i);
    EXPECT_GT(covered(expected), kSide * kSide / 20) << "layer " << i;
    EXPECT_EQ(differing(oneDraw.read(i), expected), 0u) << "layer " << i;
  }
}
