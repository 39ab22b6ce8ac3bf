// What the executor costs in GL calls (issue 26): a pass makes the calls a
// hand-written frame would make for it and no more, and a frame of the
// default pipeline binds and sets state once where hand-written GL would.
// Counted by bench/gl_call_counter.h: every GL call this program and
// librgraph make (cmake/rgraphGlCallCounter.cmake). The figures beside the
// counts are bench/render_executor_overhead.cpp's hand-written frames; the
// benchmark times both, this test holds the counts.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "chain_pipeline.h"
#include "gl_call_counter.h"
#include "rgraph/adapt.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/renderer.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/test_support.h"

namespace rgraph {
namespace {

using bench::GlCallCounter;
using Calls = std::map<std::string, long long>;

// The calls one renderFrame() makes, per GL function.
Calls frameCalls(Executor& exec) {
  const auto before = GlCallCounter::perFunction();
  exec.renderFrame();
  Calls d;
  for (const auto& [name, n] : GlCallCounter::perFunction()) d[name] += static_cast<long long>(n);
  for (const auto& [name, n] : before) d[name] -= static_cast<long long>(n);
  for (auto it = d.begin(); it != d.end();) it = it->second == 0 ? d.erase(it) : std::next(it);
  return d;
}

long long total(const Calls& calls) {
  long long n = 0;
  for (const auto& [name, k] : calls) n += k;
  return n;
}

std::string listing(const Calls& calls) {
  std::string s;
  for (const auto& [name, k] : calls) s += "  " + name + " " + std::to_string(k) + "\n";
  return s;
}

// bench/chain_pipeline.h: a gradient, then `passes` - 1 fullscreen inverts.
PipelineConfig chain(int passes) {
  return testsupport::buildPipelineOrThrow(bench::chainPipelineJson(passes), "<chain>");
}

class GlCalls : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!GlCallCounter::available()) GTEST_FAIL() << "the GL call counter needs x86-64 ELF";
    testsupport::sharedGlContext();
    shaders = std::make_unique<ShaderLibrary>();
  }
  // Built at `size`, warmed up (programs linked, first-touch allocations
  // done), per-pass CPU timing off (on llvmpipe it adds a glFinish per pass).
  std::unique_ptr<Executor> warmed(const PipelineConfig& cfg, const Scene* scene, Extent size) {
    auto exec = std::make_unique<Executor>(cfg, processRegistry(), *shaders, scene);
    exec->setCpuPassTiming(false);
    exec->resize(size);
    for (int i = 0; i < 3; ++i) exec->renderFrame();
    return exec;
  }
  std::unique_ptr<ShaderLibrary> shaders;
};

// A fullscreen pass reading the one before costs what it costs by hand: its
// framebuffer, its input's texture unit, its draw. Nothing per pass for
// state the pass leaves alone, the program and vertex array already bound,
// the viewport already set, or timing.
TEST_F(GlCalls, AFullscreenPassCostsItsFramebufferItsInputAndItsDraw) {
  auto shortChain = warmed(chain(40), nullptr, {16, 16});
  auto longChain = warmed(chain(120), nullptr, {16, 16});
  const Calls few = frameCalls(*shortChain), many = frameCalls(*longChain);
  Calls perEighty = many;
  for (const auto& [name, k] : few) perEighty[name] -= k;
  for (auto it = perEighty.begin(); it != perEighty.end();) it = it->second == 0 ? perEighty.erase(it) : std::next(it);
  const Calls expected = {{"glBindFramebuffer", 80}, {"glBindTextureUnit", 80}, {"glDrawArrays", 80}};
  EXPECT_EQ(perEighty, expected) << "80 passes more cost:\n" << listing(perEighty);
  // Per frame, beside the passes: the state a caller may have left put back
  // (10 calls), the context left neutral, one viewport, one program per shader.
  EXPECT_LE(total(few) - 3 * 40, 20) << listing(few);
}

// learnopengl:overview through pipelines/default.json at 32x32: 349 calls a
// frame (hand-written: 312; 409 before the executor kept the scene's
// bindings and passes declared what they change). Each binding is made once
// a frame, and a steady frame asks GL nothing (no glGet: a round trip on
// drivers that run GL on a thread of their own).
TEST_F(GlCalls, ADefaultPipelineFrameBindsOnceAndAsksNothing) {
  const Scene scene = loadSceneAny("learnopengl:overview");
  PipelineConfig cfg = testsupport::loadPipelineOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json");
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  auto exec = warmed(cfg, &scene, {32, 32});
  const Calls calls = frameCalls(*exec);
  const auto count = [&](const char* name) { return calls.count(name) ? calls.at(name) : 0ll; };
  EXPECT_EQ(count("glViewport"), 1) << listing(calls);
  // The Frame block when it is written, again by the first pass (the frame's
  // state reset forgets it), the light buffer once, and the scene's Objects
  // buffer (per-object matrices) for the geometry pass's draws and back to 0.
  EXPECT_EQ(count("glBindBufferBase"), 5) << listing(calls);
  EXPECT_EQ(count("glUseProgram"), 6) << listing(calls);  // five programs, program 0 at the end
  EXPECT_EQ(count("glDepthFunc"), 3) << listing(calls);  // the reset, light volumes' GL_GEQUAL and back
  EXPECT_LE(total(calls), 349) << listing(calls);
  for (const auto& [name, k] : calls) {
    EXPECT_NE(name.rfind("glGet", 0), 0u) << name << " in a steady frame";
    if (name.rfind("glIs", 0) == 0) EXPECT_EQ(name + " " + std::to_string(k), "glIsBuffer 1");  // the scene's context check
  }
  EXPECT_EQ(count("glFinish"), 0);
}

// EXT_mesh_gpu_instancing: SimpleInstancing's 125 cubes cost the draws one
// cube costs (one instanced draw per pass drawing the mesh), against the
// same scene with its instances removed (same camera, same pipeline).
TEST_F(GlCalls, InstancesCostNoDrawCallMoreThanOne) {
  const Scene instanced = loadSceneAny(std::string(RGRAPH_ASSETS_DIR) + "/gltf/SimpleInstancing/SimpleInstancing.glb");
  Scene single = instanced;
  for (Primitive& p : single.primitives) {
    p.instances.clear();
    p.bounds = p.worldBounds(single.meshes[size_t(p.mesh)].bounds);
  }
  PipelineConfig cfg = testsupport::loadPipelineOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json");
  adaptToScene(cfg, processRegistry(), sceneFeatures(instanced));
  auto draws = [&](const Scene& scene) {
    auto exec = warmed(cfg, &scene, {32, 32});
    const Calls calls = frameCalls(*exec);
    long long n = 0;
    for (const char* f : {"glDrawElements", "glDrawElementsInstanced", "glDrawArrays", "glDrawArraysInstanced"})
      n += calls.count(f) ? calls.at(f) : 0;
    return std::make_pair(n, calls.count("glDrawElementsInstanced") ? calls.at("glDrawElementsInstanced") : 0ll);
  };
  const auto [many, manyInstanced] = draws(instanced);
  const auto [one, oneInstanced] = draws(single);
  std::printf("[ measure  ] SimpleInstancing, default pipeline: %lld draw calls a frame (%lld instanced) with 125 "
              "instances, %lld with one\n",
              many, manyInstanced, one);
  EXPECT_EQ(many, one);
  EXPECT_GE(manyInstanced, 1);  // the scene's mesh, instanced
}

// The calls one Renderer::render() makes, per GL function.
Calls renderCalls(Renderer& r) {
  const auto before = GlCallCounter::perFunction();
  r.render();
  Calls d;
  for (const auto& [name, n] : GlCallCounter::perFunction()) d[name] += static_cast<long long>(n);
  for (const auto& [name, n] : before) d[name] -= static_cast<long long>(n);
  for (auto it = d.begin(); it != d.end();) it = it->second == 0 ? d.erase(it) : std::next(it);
  return d;
}

Calls minus(Calls a, const Calls& b) {
  for (const auto& [name, k] : b) a[name] -= k;
  for (auto it = a.begin(); it != a.end();) it = it->second == 0 ? a.erase(it) : std::next(it);
  return a;
}

// Picking (Renderer::requestPick) on the default pipeline at 32x32: with
// RendererOptions::picking a frame without a request costs one call more (the
// ids' clear); a frame with one adds the copy of one pixel into a pixel pack
// buffer and a fence, no glFinish and no read-back into memory.
TEST_F(GlCalls, APickCostsACopyAndAFenceNoWait) {
  auto make = [&](bool picking) {
    RendererOptions options;
    options.size = {32, 32};
    options.picking = picking;
    Diagnostics diags;
    auto r = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json", options, diags);
    EXPECT_TRUE(r);
    r->setScene(RenderScene::load("learnopengl:overview"));
    r->setCpuPassTiming(false);
    r->requestPick(16, 16);  // the pixel buffer is made by the first pick, not counted below
    for (int i = 0; i < 3; ++i) r->render();
    return r;
  };
  auto plain = make(false), picking = make(true);
  ASSERT_TRUE(plain && picking);
  const Calls off = renderCalls(*plain), idle = renderCalls(*picking);
  picking->requestPick(16, 16);
  const Calls asked = renderCalls(*picking);
  const Calls ids = minus(idle, off), pick = minus(asked, idle);
  std::printf("[ measure  ] default pipeline 32x32, Renderer::render: %lld calls, %lld with picking on, %lld with a "
              "pick requested\n",
              total(off), total(idle), total(asked));
  EXPECT_EQ(ids, (Calls{{"glClearNamedFramebufferuiv", 1}})) << listing(ids);
  for (const char* wait : {"glFinish", "glReadPixels", "glGetTextureImage", "glClientWaitSync", "glMapNamedBufferRange",
                           "glGetNamedBufferSubData"})
    EXPECT_EQ(pick.count(wait), 0u) << wait << " in a frame with a pick:\n" << listing(pick);
  EXPECT_EQ(pick.count("glGetTextureSubImage") ? pick.at("glGetTextureSubImage") : 0, 1) << listing(pick);
  EXPECT_EQ(pick.count("glFenceSync") ? pick.at("glFenceSync") : 0, 1) << listing(pick);
  // The pick's own calls: the pack buffer bound and unbound, the pack alignment, the copy, the fence and a
  // flush (6); the rest is the state the executor puts back after each pass while an after-pass callback is
  // installed (only in frames with a request): 60 at 21:25 UTC on 2026-12-06. No glGet: nothing asked.
  for (const auto& [name, k] : pick)
    EXPECT_FALSE(name.rfind("glGet", 0) == 0 && name != "glGetTextureSubImage") << name << " in a frame with a pick";
  EXPECT_EQ(pick.at("glBindBuffer"), 2) << listing(pick);
  EXPECT_LE(total(pick), 70) << listing(pick);
}

}  // namespace
}  // namespace rgraph
