// Scene objects moved every frame through the public API (issue 30):
// 1,000 instances of one mesh made in code (RenderScene::addMesh, uploaded
// once), every one given a new transform each frame (setTransform), drawn by
// pipelines/default.json through a Renderer at 64x64, against the same
// scene left still, side by side.
//
//   BM_Instances/moving, BM_Instances/still: per frame, the calling thread's
//   CPU time for the moves plus render() (llvmpipe rasterises on threads of
//   its own: this is the API, the draws' submission and state validation),
//   and as counters:
//     cpu_ms_per_frame        that CPU time (median over the frames)
//     move_cpu_ms_per_frame   the 1,000 setTransform calls alone
//     geometry_bytes_per_frame  vertex and index bytes uploaded (GpuScene::geometryBytes): 0
//     object_bytes_per_frame  bytes written into the scene's Objects buffer (GpuScene::objectBytes:
//                             model, previous model and normal matrix of each object that changed)
//     draw_bytes_per_frame    per-draw uniforms the scene's draws set (GpuScene::drawUniformBytes:
//                             the draw's entry in Objects, the material's uniforms)
//     gl_objects_per_frame    GL objects created (gl::createdObjectsTotal): 0
//     gl_create_calls_per_frame  glCreate* and glGen* calls of any caller (gl_call_counter.h): 0
//     gl_calls_per_frame      every GL call of the frame (gl_call_counter.h)
//     builds                  pipeline builds over the run (Renderer::builds): 1
// A frame whose moves created GL objects, rebuilt the pipeline or uploaded
// geometry makes the benchmark report an error.
#include <GL/glcorearb.h>
#include <benchmark/benchmark.h>
#include <time.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl_call_counter.h"
#include "render_context.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "../apps/rgraph/median.h"

namespace {
using namespace rgraph;

constexpr int kSide = 10;  // 10 x 10 x 10 = 1,000 instances
constexpr Extent kSize{64, 64};

// glCreate* and glGen* calls so far (every GL object made, by rgraph's wrappers or not).
double createCalls() {
  double n = 0;
  for (const auto& [name, count] : bench::GlCallCounter::perFunction())
    if (name.rfind("glCreate", 0) == 0 || name.rfind("glGen", 0) == 0) n += double(count);
  return n;
}

double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

struct World {
  std::shared_ptr<RenderScene> scene;
  std::unique_ptr<Renderer> renderer;
  std::vector<InstanceId> ids;
  std::vector<glm::vec3> places;
};

World& world() {
  return bench::contextSingleton<World>([] {
    auto w = std::make_unique<World>();
    Scene s;
    s.source = "instances:1000";
    s.materials.push_back(Material{});
    s.directionalLights.push_back(DirectionalLight{});
    s.camera.position = {0.0f, 8.0f, 30.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.hasCamera = true;
    w->scene = RenderScene::fromScene(std::move(s));
    const size_t cube = w->scene->addMesh(makeCube(0.3f));
    for (int i = 0; i < kSide * kSide * kSide; ++i) {
      const glm::vec3 p(float(i % kSide) - 4.5f, float(i / kSide % kSide) - 4.5f, float(i / (kSide * kSide)) - 4.5f);
      w->places.push_back(p * 1.5f);
      w->ids.push_back(w->scene->addInstance(cube, 0, glm::translate(glm::mat4(1.0f), w->places.back())));
    }
    RendererOptions options;
    options.size = kSize;
    Diagnostics diags;
    w->renderer = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json", options, diags);
    if (!w->renderer) throw RuntimeError("pipelines/default.json did not load");
    w->renderer->setScene(w->scene);
    w->renderer->setCpuPassTiming(false);  // (on llvmpipe it adds a glFinish per pass)
    for (int i = 0; i < 3; ++i) w->renderer->render();
    glFinish();
    return w;
  });
}

// Every instance turned about its own vertical axis and bobbed: a new matrix each frame.
void moveAll(World& w, uint64_t frame) {
  for (size_t i = 0; i < w.ids.size(); ++i) {
    const float t = float(frame) * 0.05f + float(i) * 0.01f;
    glm::mat4 m = glm::translate(glm::mat4(1.0f), w.places[i] + glm::vec3(0.0f, 0.2f * std::sin(t), 0.0f));
    w.scene->setTransform(w.ids[i], glm::rotate(m, t, glm::vec3(0.0f, 1.0f, 0.0f)));
  }
}

void BM_Instances(benchmark::State& state, bool moving) {
  World* w = bench::worldOrSkip(state, world);
  if (!w) return;
  GpuScene& gpu = w->scene->gpu();
  const uint64_t builds = w->renderer->builds();
  const uint64_t geometry = gpu.geometryBytes(), drawBytes = gpu.drawUniformBytes(), objectBytes = gpu.objectBytes();
  const int64_t objects = gl::createdObjectsTotal();
  const uint64_t calls = bench::GlCallCounter::total();
  const double creates = createCalls();
  std::vector<double> frameMs, moveMs;
  uint64_t frame = 0;
  for (auto _ : state) {
    const double t0 = threadCpuMs();
    if (moving) moveAll(*w, ++frame);
    const double t1 = threadCpuMs();
    w->renderer->render();
    const double t2 = threadCpuMs();
    glFinish();  // the frame done before the next one starts (not timed)
    moveMs.push_back(t1 - t0);
    frameMs.push_back(t2 - t0);
  }
  const double frames = double(frameMs.size());
  if (gl::createdObjectsTotal() != objects || createCalls() != creates || w->renderer->builds() != builds || gpu.geometryBytes() != geometry) {
    state.SkipWithError("a steady frame created GL objects, rebuilt the pipeline or uploaded geometry");
    return;
  }
  state.counters["cpu_ms_per_frame"] = cli::median(frameMs);
  state.counters["move_cpu_ms_per_frame"] = cli::median(moveMs);
  state.counters["geometry_bytes_per_frame"] = double(gpu.geometryBytes() - geometry) / frames;
  state.counters["object_bytes_per_frame"] = double(gpu.objectBytes() - objectBytes) / frames;
  state.counters["draw_bytes_per_frame"] = double(gpu.drawUniformBytes() - drawBytes) / frames;
  state.counters["gl_objects_per_frame"] = double(gl::createdObjectsTotal() - objects) / frames;
  state.counters["gl_create_calls_per_frame"] = (createCalls() - creates) / frames;
  state.counters["gl_calls_per_frame"] = double(bench::GlCallCounter::total() - calls) / frames;
  state.counters["instances"] = double(w->ids.size());
  state.counters["builds"] = double(w->renderer->builds());
}

BENCHMARK_CAPTURE(BM_Instances, moving, true)->Unit(benchmark::kMillisecond)->Iterations(60);
BENCHMARK_CAPTURE(BM_Instances, still, false)->Unit(benchmark::kMillisecond)->Iterations(60);

}  // namespace
