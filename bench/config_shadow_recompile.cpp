// What a change of the shadowed lights costs the CPU (issue 28): when a light
// enters or leaves the view or the budget, the Renderer derives the scene's
// features again, adapts the pipeline as loaded (the shadow_map template
// expanded into one pass per cascade, spot map and point cube) and compiles
// the graph. Target: under 1 ms with 64 shadowed lights in each shipped
// shadow pipeline. Timed: sceneFeatures + adaptToScene + compile, from a copy
// of the loaded pipeline (the Renderer adapts a copy of its source each time);
// the GL side of a rebuild (executor, textures) is not in this figure.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "rgraph/adapt.h"
#include "rgraph/graph.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace {
using namespace rgraph;

const char* const kPipelines[] = {"deferred-pbr-shadows.json", "deferred-shadows.json",
                                  "deferred-clustered-shadows.json"};

// scenes/shadows.json with `lights` more casting lights on a ring over its
// floor, all in view: spot lights looking down (kind 0) or point lights (1).
Scene sceneWithLights(int lights, bool point) {
  Scene s = loadSceneAny(std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json");
  s.pointLights.clear();
  for (int i = 0; i < lights; ++i) {
    const float a = 6.2831853f * float(i) / float(lights);
    PointLight l;
    l.position = glm::vec3(3.0f * std::cos(a), 2.0f + 0.02f * float(i), 3.0f * std::sin(a));
    l.color = glm::vec3(1.0f);
    l.castShadows = true;
    l.spot = !point;
    l.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    l.innerConeDeg = 30.0f;
    l.outerConeDeg = 40.0f;
    s.pointLights.push_back(l);
  }
  return s;
}

void BM_ShadowRecompile(benchmark::State& state) {
  const char* file = kPipelines[state.range(0)];
  const int lights = static_cast<int>(state.range(1));
  PipelineConfig loaded = loadPipelineFileOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + file);
  for (auto& pass : loaded.params)
    if (pass.has("max_lights")) pass.set("max_lights", int64_t{64});
  const Scene scene = sceneWithLights(lights, state.range(2) != 0);
  const PassRegistry& registry = processRegistry();
  size_t passes = 0, live = 0, shadowed = 0;
  for (auto _ : state) {
    PipelineConfig adapted = loaded;
    const SceneFeatures features = sceneFeatures(scene, scene.camera, 16.0f / 9.0f);
    adaptToScene(adapted, registry, features);
    CompileOptions options;
    options.output = Extent{1280, 720};
    Plan plan = compile(adapted.graph, options);
    if (!plan.ok()) {
      state.SkipWithError("the adapted pipeline does not compile");
      break;
    }
    passes = adapted.graph.passes.size();
    live = plan.order.size();
    shadowed = features.shadowLights.size();
    benchmark::DoNotOptimize(plan);
  }
  state.SetLabel(file);
  state.counters["shadowed_lights"] = static_cast<double>(shadowed);
  state.counters["passes"] = static_cast<double>(passes);
  state.counters["live_passes"] = static_cast<double>(live);
}

// Args: pipeline (index into kPipelines), casting lights added, point (1) or spot (0).
BENCHMARK(BM_ShadowRecompile)
    ->ArgNames({"pipeline", "lights", "point"})
    ->ArgsProduct({{0, 1, 2}, {64}, {0, 1}})
    ->Args({0, 8, 0})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

namespace {
// The three steps apart (pipeline 0, 64 point lights): which one to speed up.
void BM_ShadowRecompileStep(benchmark::State& state) {
  PipelineConfig loaded =
      loadPipelineFileOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr-shadows.json");
  for (auto& pass : loaded.params)
    if (pass.has("max_lights")) pass.set("max_lights", int64_t{64});
  const Scene scene = sceneWithLights(64, true);
  const PassRegistry& registry = processRegistry();
  const SceneFeatures features = sceneFeatures(scene, scene.camera, 16.0f / 9.0f);
  PipelineConfig adapted = loaded;
  adaptToScene(adapted, registry, features);
  CompileOptions options;
  options.output = Extent{1280, 720};
  for (auto _ : state) {
    if (state.range(0) == 0) {
      benchmark::DoNotOptimize(sceneFeatures(scene, scene.camera, 16.0f / 9.0f));
    } else if (state.range(0) == 1) {
      PipelineConfig copy = loaded;
      benchmark::DoNotOptimize(adaptToScene(copy, registry, features));
    } else if (state.range(0) == 2) {
      PipelineConfig copy = loaded;
      benchmark::DoNotOptimize(copy);
    } else {
      benchmark::DoNotOptimize(compile(adapted.graph, options));
    }
  }
  state.SetLabel(state.range(0) == 0 ? "sceneFeatures" : state.range(0) == 1 ? "copy + adaptToScene"
                                                     : state.range(0) == 2 ? "copy"
                                                                           : "compile");
}
BENCHMARK(BM_ShadowRecompileStep)->ArgName("step")->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
}  // namespace
