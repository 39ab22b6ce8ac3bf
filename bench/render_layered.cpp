// Drawing the scene into every layer of a layered target (issue 27): one
// instanced draw per primitive writing each layer through gl_Layer from the
// vertex shader (GpuScene::drawLayered) against one draw per layer with the
// layer attached in between (GpuScene::drawEachLayer), side by side.
//
// BM_LayeredPaired/<case> alternates the two frame for frame (both cleared
// the same way, glFinish after each, wall clock: llvmpipe's timer queries are
// wrong, ../shared/PLATFORM.md) and reports each one's median and the median
// of the per-pair ratios per_layer / layered ("speedup": above 1, the layered
// draw is faster; speedup_min: the smallest pair's; bench/paired_times.h).
// Before timing, the two paths' layers are compared and must be equal byte
// for byte (else the benchmark is skipped with an error).
//
// Cases: cube (6 faces of a 256x256 cube map, a point light's shadow map)
// and array16 (16 layers of a 128x128 2D array, e.g. cascades or an atlas),
// rgba8 colour and depth32f; scene.vert with solid_color.frag.
// Environment: RGRAPH_BENCH_SCENE (default learnopengl).
#include <GL/glcorearb.h>
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <cstdlib>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "paired_times.h"
#include "render_context.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/scene.h"

namespace {
using namespace rgraph;
using Clock = std::chrono::steady_clock;

struct Layered {
  GLenum target;
  uint32_t side;
  int layers;
  gl::Texture color, depth;
  gl::Framebuffer fbo;
  std::vector<GpuScene::View> views;

  Layered(GLenum t, uint32_t s, int n, glm::vec3 eye) : target(t), side(s), layers(n) {
    color = gl::createTexture(target);
    depth = gl::createTexture(target);
    if (target == GL_TEXTURE_2D_ARRAY) {
      glTextureStorage3D(color.id(), 1, GL_RGBA8, side, side, layers);
      glTextureStorage3D(depth.id(), 1, GL_DEPTH_COMPONENT32F, side, side, layers);
    } else {
      glTextureStorage2D(color.id(), 1, GL_RGBA8, side, side);
      glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, side, side);
    }
    fbo = gl::createFramebuffer();
    // One view per layer around `eye`: a cube map's six faces, or N
    // directions around the vertical for an array.
    const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    for (int i = 0; i < layers; ++i) {
      GpuScene::View v;
      if (target == GL_TEXTURE_CUBE_MAP) {
        v.view = glm::lookAt(eye, eye + dirs[i], ups[i]);
      } else {
        const float a = glm::two_pi<float>() * float(i) / float(layers);
        v.view = glm::lookAt(eye, eye + glm::vec3(std::cos(a), -0.3f, std::sin(a)), glm::vec3(0, 1, 0));
      }
      v.proj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 100.0f);
      v.cull = GpuScene::Cull::none;
      views.push_back(v);
    }
  }
  void clear() const {
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &one);
  }
  void attach(int layer) const {
    if (layer < 0) {
      glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
      glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    } else {
      glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0, layer);
      glNamedFramebufferTextureLayer(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0, layer);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, GLsizei(side), GLsizei(side));
    clear();
  }
  std::vector<uint8_t> readAll() const {
    std::vector<uint8_t> px(size_t(side) * side * 4 * layers);
    glGetTextureImage(color.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    return px;
  }
};

struct World {
  Scene scene;
  std::unique_ptr<GpuScene> gpu;
  std::unique_ptr<ShaderLibrary> shaders;
  uint32_t perLayerProgram = 0, layeredProgram = 0;
  std::unique_ptr<Layered> cube, array16;
};

World& world() {
  return bench::contextSingleton<World>([] {
    auto w = std::make_unique<World>();
    const char* spec = std::getenv("RGRAPH_BENCH_SCENE");
    w->scene = loadSceneAny(spec && *spec ? spec : "learnopengl");
    w->gpu = std::make_unique<GpuScene>(w->scene);
    w->gpu->updateFrame({256, 256});
    w->shaders = std::make_unique<ShaderLibrary>();
    w->perLayerProgram = w->shaders->program("scene.vert", "solid_color.frag");
    if (w->gpu->supportsLayeredDraw())
      w->layeredProgram = w->shaders->program("scene.vert", "solid_color.frag", {"LAYERED"});
    for (uint32_t p : {w->perLayerProgram, w->layeredProgram})
      if (p) glProgramUniform4f(p, glGetUniformLocation(p, "u_color"), 1.0f, 0.5f, 0.25f, 1.0f);
    const glm::vec3 eye = w->scene.bounds().center() + glm::vec3(0.0f, 0.5f, 0.0f);
    w->cube = std::make_unique<Layered>(GL_TEXTURE_CUBE_MAP, 256, 6, eye);
    w->array16 = std::make_unique<Layered>(GL_TEXTURE_2D_ARRAY, 128, 16, eye);
    return w;
  });
}

double timed(const std::function<void()>& draw) {
  glFinish();
  const auto t0 = Clock::now();
  draw();
  glFinish();
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void BM_LayeredPaired(benchmark::State& state, std::unique_ptr<Layered> World::*which) {
  World* w = bench::worldOrSkip(state, world);
  if (!w) return;
  if (!w->gpu->supportsLayeredDraw()) {
    state.SkipWithError("no gl_Layer from the vertex shader on this device");
    return;
  }
  const Layered& t = *(w->*which);
  glEnable(GL_DEPTH_TEST);
  auto perLayer = [&] {
    w->gpu->drawEachLayer(w->perLayerProgram, t.views, [&](size_t i) { t.attach(int(i)); });
  };
  auto layered = [&] {
    t.attach(-1);
    w->gpu->drawLayered(w->layeredProgram, t.views);
  };
  perLayer();
  const std::vector<uint8_t> want = t.readAll();
  layered();
  if (t.readAll() != want) {
    glDisable(GL_DEPTH_TEST);
    state.SkipWithError("the layered draw's layers differ from the per-layer draws'");
    return;
  }
  bench::PairedTimes times;
  for (auto _ : state) {
    const double x = timed(perLayer);
    times.add(state, x, timed(layered));
  }
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  times.report(state, "per_layer", "layered");
  state.counters["draws_per_layer"] = double(w->gpu->primitiveCount(GpuScene::Filter::opaque)) * t.layers;
  state.counters["draws_layered"] = double(w->gpu->primitiveCount(GpuScene::Filter::opaque));
  state.SetLabel(std::to_string(t.layers) + " layers of " + std::to_string(t.side) + "x" + std::to_string(t.side) +
                 ", " + w->scene.source);
}

BENCHMARK_CAPTURE(BM_LayeredPaired, cube, &World::cube)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(40);
BENCHMARK_CAPTURE(BM_LayeredPaired, array16, &World::array16)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(40);

}  // namespace
