// What the executor costs (issue 15): a pipeline run through Executor against
// the same GL work written out by hand in this file: the same programs, the
// same textures, the same draws in the same order, with the binds and state
// changes a careful programmer would make (state that does not change between
// draws set once per frame, constant uniforms set once at setup, the context
// left neutral at the end of the frame, as the executor leaves it).
//
//   BM_ExecutorOverhead/chain200_16x16: 200 fullscreen passes on 16x16
//     targets (a gradient, then 199 inverts, each reading the previous one).
//   BM_ExecutorOverhead/default_32x32: pipelines/default.json (deferred, light
//     volumes, light markers, tone map) on learnopengl:overview at 32x32.
//
// Each iteration renders one frame each way, alternating which goes first,
// and times the calling thread's CPU time over the frame and a glFinish
// (llvmpipe rasterises on threads of its own; the submitting thread's time is
// the API, state validation and binning). ratio_vs_hand_written is the median
// of the per-pair ratios executor / hand-written: robust on a shared machine.
// gl_calls_* count every GL call each frame makes (gl_call_counter.h).
// Before timing, both outputs are compared: the hand-written frame must
// produce the executor's image exactly (else the benchmark reports an error).
// The executor runs with per-pass CPU timing off (Executor::setCpuPassTiming:
// on software renderers it adds a glFinish per pass); its passes as shipped.
//
// RGRAPH_BENCH_GL_BREAKDOWN=1 prints the calls of one frame per GL function.
#include <GL/glcorearb.h>
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "chain_pipeline.h"
#include "gl_call_counter.h"
#include "render_context.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/light_volume_meshes.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "../apps/rgraph/median.h"

namespace {
using namespace rgraph;
using bench::GlCallCounter;

double threadCpuUs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double wallUs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

using rgraph::cli::median;  // the median render --stats and rgraph bench report

// One pipeline two ways: through an Executor, and written out.
struct Case {
  std::string error;  // set up failed or the images differ
  std::unique_ptr<Scene> scene;
  std::unique_ptr<Executor> exec;
  std::function<void()> hand;  // one hand-written frame
  std::vector<gl::Framebuffer> fbos;
  gl::VertexArray vao;
  size_t passes = 0;
  uint64_t handFrame = 0;
};

struct World {
  std::unique_ptr<ShaderLibrary> shaders;
  std::map<std::string, Case> cases;
};

// Program `index` of a pass, as the executor asked the ShaderLibrary for it
// (the library caches: the same GL program object).
uint32_t programOf(const Executor& exec, ShaderLibrary& shaders, const std::string& pass, size_t index = 0) {
  for (const auto& b : exec.builtPrograms())
    if (b.pass == pass && index-- == 0) {
      const ProgramRequest& r = b.program;
      return r.comp.empty() ? shaders.program(r.vert, r.frag, r.defines) : shaders.computeProgram(r.comp, r.defines);
    }
  throw RuntimeError("no program " + std::to_string(index) + " for pass '" + pass + "'");
}

gl::Framebuffer framebuffer(std::initializer_list<std::pair<GLenum, uint32_t>> attachments) {
  gl::Framebuffer f = gl::createFramebuffer();
  std::vector<GLenum> draw;
  for (const auto& [point, texture] : attachments) {
    glNamedFramebufferTexture(f.id(), point, texture, 0);
    if (point >= GL_COLOR_ATTACHMENT0 && point < GL_COLOR_ATTACHMENT0 + 8) draw.push_back(point);
  }
  if (draw.empty())
    glNamedFramebufferDrawBuffer(f.id(), GL_NONE);
  else
    glNamedFramebufferDrawBuffers(f.id(), static_cast<GLsizei>(draw.size()), draw.data());
  if (glCheckNamedFramebufferStatus(f.id(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RuntimeError("hand-written framebuffer incomplete");
  return f;
}

std::unique_ptr<Executor> makeExecutor(const PipelineConfig& cfg, World& w, const Scene* scene, Extent size) {
  auto exec = std::make_unique<Executor>(cfg, processRegistry(), *w.shaders, scene);
  exec->setCpuPassTiming(false);
  exec->resize(size);
  return exec;
}

// ------------------------------------------------------------ chain of 200

constexpr int kChain = 200;

void setUpChain(World& w, Case& c) {
  const PipelineConfig cfg = loadPipelineTextOrThrow(bench::chainPipelineJson(kChain), "<chain>");
  c.exec = makeExecutor(cfg, w, nullptr, {16, 16});
  c.passes = kChain;

  // The executor's textures (aliased: a few physical ones), one framebuffer per texture.
  std::vector<uint32_t> tex(kChain);
  std::map<uint32_t, size_t> fboOf;
  for (int i = 0; i < kChain; ++i) {
    tex[i] = c.exec->textureOf("t" + std::to_string(i));
    if (!fboOf.count(tex[i])) {
      fboOf[tex[i]] = c.fbos.size();
      c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, tex[i]}}));
    }
  }
  std::vector<uint32_t> fbo(kChain);
  for (int i = 0; i < kChain; ++i) fbo[i] = c.fbos[fboOf[tex[i]]].id();
  const uint32_t gradient = programOf(*c.exec, *w.shaders, "p0"), invert = programOf(*c.exec, *w.shaders, "p1");
  c.vao = gl::createVertexArray();
  c.hand = [&c, tex, fbo, gradient, invert] {
    glViewport(0, 0, 16, 16);
    glBindVertexArray(c.vao.id());
    glUseProgram(gradient);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[0]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glUseProgram(invert);
    for (int i = 1; i < kChain; ++i) {
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo[i]);
      glBindTextureUnit(0, tex[i - 1]);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
  };
}

// ------------------------------------------------- default.json, by hand

void setUpDefault(World& w, Case& c) {
  c.scene = std::make_unique<Scene>(loadSceneAny("learnopengl:overview"));
  PipelineConfig cfg = loadPipelineFileOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json");
  adaptToScene(cfg, processRegistry(), sceneFeatures(*c.scene));
  const Extent size{32, 32};
  c.exec = makeExecutor(cfg, w, c.scene.get(), size);
  Executor& e = *c.exec;
  c.passes = e.plan().order.size();
  std::vector<std::string> order;
  for (PassIndex p : e.plan().order) order.push_back(cfg.graph.passes[p.value()].name);
  const std::vector<std::string> expected = {"gbuffer", "ambient", "light_volumes", "depth_blit", "light_boxes",
                                             "tonemap"};
  if (order != expected) throw RuntimeError("default.json's passes changed: update the hand-written frame");
  GpuScene& gpu = *e.gpuScene();
  if (gpu.primitiveCount(GpuScene::Filter::blend) != 0 || gpu.pointLightCount() == 0)
    throw RuntimeError("the scene changed: the hand-written frame draws no blended surfaces and needs point lights");

  auto t = [&](const char* name) { return e.textureOf(name); };
  const uint32_t gPosition = t("gPosition"), gNormal = t("gNormal"), gAlbedo = t("gAlbedoSpec"), gDepth = t("gDepth"),
                 hdr = t("hdr"), fDepth = t("forwardDepth"), output = t("output");
  c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, gPosition},
                                {GL_COLOR_ATTACHMENT1, gNormal},
                                {GL_COLOR_ATTACHMENT2, gAlbedo},
                                {GL_DEPTH_STENCIL_ATTACHMENT, gDepth}}));
  c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, hdr}}));
  c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, hdr}, {GL_DEPTH_STENCIL_ATTACHMENT, gDepth}}));
  c.fbos.push_back(framebuffer({{GL_DEPTH_STENCIL_ATTACHMENT, fDepth}}));
  c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, hdr}, {GL_DEPTH_STENCIL_ATTACHMENT, fDepth}}));
  c.fbos.push_back(framebuffer({{GL_COLOR_ATTACHMENT0, output}}));
  const uint32_t gbufferFbo = c.fbos[0].id(), hdrFbo = c.fbos[1].id(), volumesFbo = c.fbos[2].id(),
                 depthCopyFbo = c.fbos[3].id(), markersFbo = c.fbos[4].id(), outputFbo = c.fbos[5].id();
  gl::Framebuffer depthRead = framebuffer({{GL_DEPTH_STENCIL_ATTACHMENT, gDepth}});
  glNamedFramebufferReadBuffer(depthRead.id(), GL_NONE);
  c.fbos.push_back(std::move(depthRead));
  const uint32_t depthReadFbo = c.fbos.back().id();

  const uint32_t geometry = programOf(e, *w.shaders, "gbuffer"), ambient = programOf(e, *w.shaders, "ambient"),
                 volumes = programOf(e, *w.shaders, "light_volumes"),
                 markers = programOf(e, *w.shaders, "light_boxes"), tonemap = programOf(e, *w.shaders, "tonemap");
  // Constant uniforms, once (the passes set them every frame: their programs may be shared).
  auto uniform = [](uint32_t p, const char* n) { return glGetUniformLocation(p, n); };
  glProgramUniform1i(ambient, uniform(ambient, "u_pointLightCount"), 0);
  glProgramUniform1i(ambient, uniform(ambient, "u_ambientAndSun"), 1);
  glProgramUniform1i(ambient, uniform(ambient, "u_hasAo"), 0);
  const GLint firstLightLoc = uniform(volumes, "u_firstLight"), spotVolumesLoc = uniform(volumes, "u_spotVolumes");
  const GLint volumeScaleLoc = uniform(volumes, "u_volumeScale");
  const light_volumes::Meshes& meshes = light_volumes::Meshes::of(gpu);
  const float icosphereScale = meshes.icosphereScale();
  glProgramUniform1f(markers, uniform(markers, "u_markerSize"), 0.125f);
  glProgramUniform1f(tonemap, uniform(tonemap, "u_exposure"), 1.0f);
  glProgramUniform1i(tonemap, uniform(tonemap, "u_operator"), 2);  // "none"
  glProgramUniform1i(tonemap, uniform(tonemap, "u_encodeSrgb"), 1);
  glProgramUniform1f(tonemap, uniform(tonemap, "u_gamma"), 1.0f);
  const uint32_t lights = gpu.pointLightCount();
  const float threshold = 5.0f / 256.0f;  // every pass's cut-off: one light buffer
  c.vao = gl::createVertexArray();

  c.hand = [&c, &gpu, size, lights, threshold, gPosition, gNormal, gAlbedo, hdr, gbufferFbo, hdrFbo, volumesFbo,
            depthCopyFbo, markersFbo, outputFbo, depthReadFbo, geometry, ambient, volumes, markers, tonemap, firstLightLoc,
            spotVolumesLoc, volumeScaleLoc, icosphereScale, &meshes] {
    FrameMotion motion;
    motion.frame = c.handFrame++;
    gpu.updateFrame(size, gpu.scene().camera, motion);  // binds the Frame block
    lighting::bindPointLights(gpu, threshold);
    glViewport(0, 0, static_cast<GLsizei>(size.width), static_cast<GLsizei>(size.height));
    // gbuffer
    const float zero[4] = {0, 0, 0, 0}, black[4] = {0, 0, 0, 1}, one = 1.0f;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gbufferFbo);
    for (int i = 0; i < 3; ++i) glClearNamedFramebufferfv(gbufferFbo, GL_COLOR, i, zero);
    glEnable(GL_DEPTH_TEST);
    glClearNamedFramebufferfv(gbufferFbo, GL_DEPTH, 0, &one);
    gpu.drawPrimitives(geometry, {});
    glDisable(GL_DEPTH_TEST);
    // ambient: clears hdr, reads the G-buffer
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, hdrFbo);
    glClearNamedFramebufferfv(hdrFbo, GL_COLOR, 0, black);
    glBindTextureUnit(0, gPosition);
    glBindTextureUnit(1, gNormal);
    glBindTextureUnit(2, gAlbedo);
    glUseProgram(ambient);
    glBindVertexArray(c.vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // light_volumes: far faces, depth-tested against the G-buffer's, added
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, volumesFbo);
    glUseProgram(volumes);
    // The scene has no spot lights, so a frame written alone would set these
    // once; the executor's frames, alternated with this one on the same
    // program, leave them at the spot cones' values.
    glUniform1i(firstLightLoc, 0);
    glUniform1i(spotVolumesLoc, 0);
    glUniform1f(volumeScaleLoc, icosphereScale);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    meshes.drawIcosphere(nullptr, lights);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_CLAMP);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    // depth_blit
    glBlitNamedFramebuffer(depthReadFbo, depthCopyFbo, 0, 0, static_cast<GLint>(size.width),
                           static_cast<GLint>(size.height), 0, 0, static_cast<GLint>(size.width),
                           static_cast<GLint>(size.height), GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, GL_NEAREST);
    // light_boxes: depth test and cull still on
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, markersFbo);
    glUseProgram(markers);
    glCullFace(GL_BACK);
    meshes.drawCube(nullptr, lights);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    // tonemap
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, outputFbo);
    glBindTextureUnit(0, hdr);
    glUseProgram(tonemap);
    glBindVertexArray(c.vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    for (GLuint unit = 0; unit < 3; ++unit) glBindTextureUnit(unit, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
  };
}

// ------------------------------------------------------------ the world

// The hand-written frame must leave the executor's image in the output.
void checkSameImage(Case& c) {
  for (int i = 0; i < 3; ++i) c.exec->renderFrame();  // compiles, first-touch allocations
  glFinish();
  const std::vector<uint8_t> want = c.exec->readOutputRGBA8();
  const float clear[4] = {0.5f, 0.25f, 0.75f, 1.0f};
  glClearTexImage(c.exec->outputTexture(), 0, GL_RGBA, GL_FLOAT, clear);
  for (int i = 0; i < 3; ++i) c.hand();
  glFinish();
  const std::vector<uint8_t> got = c.exec->readOutputRGBA8();
  if (got != want) c.error = "the hand-written frame's image differs from the executor's";
  bool flat = true;
  for (size_t i = 4; i < want.size(); ++i) flat = flat && want[i] == want[i % 4];
  if (flat) c.error = "the executor's image is one colour: nothing to compare";
}

std::unique_ptr<World> makeWorld() {
  auto w = std::make_unique<World>();
  w->shaders = std::make_unique<ShaderLibrary>();
  const std::pair<const char*, void (*)(World&, Case&)> cases[] = {{"chain200_16x16", setUpChain},
                                                                   {"default_32x32", setUpDefault}};
  for (const auto& [name, setUp] : cases) {
    Case& c = w->cases[name];
    try {
      setUp(*w, c);
      checkSameImage(c);
    } catch (const std::exception& e) {
      c.error = e.what();
    }
  }
  return w;
}

World& world() { return bench::contextSingleton<World>(makeWorld); }

struct Sample {
  double cpuUs = 0, wallUs = 0;
  uint64_t calls = 0;
};

template <typename F>
Sample timed(F&& frame) {
  const uint64_t calls0 = GlCallCounter::total();
  const double w0 = wallUs(), c0 = threadCpuUs();
  frame();
  glFinish();
  Sample s{threadCpuUs() - c0, wallUs() - w0, 0};
  s.calls = GlCallCounter::total() - calls0 - 1;  // not the glFinish
  return s;
}

void printBreakdown(const std::string& name, Case& c) {
  auto frameCalls = [](const std::function<void()>& f) {
    const auto before = GlCallCounter::perFunction();
    f();
    std::map<std::string, long long> d;
    for (const auto& [n, k] : GlCallCounter::perFunction()) d[n] += static_cast<long long>(k);
    for (const auto& [n, k] : before) d[n] -= static_cast<long long>(k);
    return d;
  };
  const auto ex = frameCalls([&] { c.exec->renderFrame(); });
  const auto hw = frameCalls(c.hand);
  std::map<std::string, std::pair<long long, long long>> both;
  for (const auto& [n, k] : ex) both[n].first = k;
  for (const auto& [n, k] : hw) both[n].second = k;
  std::fprintf(stderr, "%s: GL calls in one frame (executor, hand-written)\n", name.c_str());
  for (const auto& [n, k] : both)
    if (k.first || k.second) std::fprintf(stderr, "  %-32s %6lld %6lld\n", n.c_str(), k.first, k.second);
  glFinish();
}

void BM_ExecutorOverhead(benchmark::State& state, std::string name) {
  World* w = bench::worldOrSkip(state, world);
  if (!w) return;
  Case& c = w->cases[name];
  if (!c.error.empty()) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  if (const char* b = std::getenv("RGRAPH_BENCH_GL_BREAKDOWN"); b && *b == '1') printBreakdown(name, c);
  std::vector<double> ratio, ratioWall, exCpu, hwCpu, exWall, hwWall;
  uint64_t exCalls = 0, hwCalls = 0;
  bool executorFirst = true;
  for (auto _ : state) {
    Sample ex, hw;
    if (executorFirst) {
      ex = timed([&] { c.exec->renderFrame(); });
      hw = timed(c.hand);
    } else {
      hw = timed(c.hand);
      ex = timed([&] { c.exec->renderFrame(); });
    }
    executorFirst = !executorFirst;
    ratio.push_back(ex.cpuUs / hw.cpuUs);
    ratioWall.push_back(ex.wallUs / hw.wallUs);
    exCpu.push_back(ex.cpuUs);
    hwCpu.push_back(hw.cpuUs);
    exWall.push_back(ex.wallUs);
    hwWall.push_back(hw.wallUs);
    exCalls = ex.calls;
    hwCalls = hw.calls;
    state.SetIterationTime((ex.cpuUs + hw.cpuUs) * 1e-6);
  }
  state.counters["ratio_vs_hand_written"] = median(ratio);
  state.counters["ratio_wall"] = median(ratioWall);
  state.counters["executor_cpu_us"] = median(exCpu);
  state.counters["hand_cpu_us"] = median(hwCpu);
  state.counters["executor_wall_us"] = median(exWall);
  state.counters["hand_wall_us"] = median(hwWall);
  if (GlCallCounter::available()) {
    state.counters["gl_calls_executor"] = static_cast<double>(exCalls);
    state.counters["gl_calls_hand"] = static_cast<double>(hwCalls);
  }
  state.counters["passes"] = static_cast<double>(c.passes);
}

struct Register {
  Register() {
    for (const char* name : {"chain200_16x16", "default_32x32"})
      benchmark::RegisterBenchmark((std::string("BM_ExecutorOverhead/") + name).c_str(), BM_ExecutorOverhead,
                                   std::string(name))
          ->UseManualTime()
          ->Unit(benchmark::kMicrosecond)
          ->Iterations(300);
  }
} registerOnce;

}  // namespace
