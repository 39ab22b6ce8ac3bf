// The exact-visibility oracle (issue 28, tests/support/visibility_oracle.h):
// BVH build time, and shadow rays per second through the BVH against brute
// force (every triangle tested) on the same rays, side by side in one run.
// Scenes: DamagedHelmet (the biggest glTF asset in ../shared/assets) and the
// learnopengl procedural scene (small). Probes are surface points found by
// camera rays (closest hit) before the timed loop; each timed ray goes from a
// probe (offset along its face normal) towards a directional light.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>

#include <rgraph/scene.h>

#include "visibility_oracle.h"

namespace {

using namespace rgraph;
using namespace rgraph::oracle;

struct Fixture {
  Scene scene;
  std::vector<WorldTriangle> triangles;
  std::unique_ptr<VisibilityOracle> oracle;
  std::vector<Ray> shadowRays;  // from surface points towards the sun
  std::vector<VisibilityOracle::Probe> probes;
};

Scene loadBenchScene(int which) {
  if (which == 0) return loadGltf(std::string(RGRAPH_ASSETS_DIR) + "/gltf/DamagedHelmet/DamagedHelmet.glb");
  return loadSceneAny("learnopengl");
}

const char* sceneName(int which) { return which == 0 ? "DamagedHelmet" : "learnopengl"; }

DirectionalLight benchSun() {
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
  return sun;
}

Fixture& fixture(int which) {
  static std::map<int, Fixture> cache;
  auto it = cache.find(which);
  if (it != cache.end()) return it->second;
  Fixture& f = cache[which];
  f.scene = loadBenchScene(which);
  f.triangles = shadowCasterTriangles(f.scene);
  f.oracle = std::make_unique<VisibilityOracle>(f.scene);
  const dvec3 lo = f.oracle->bvh().boundsMin(), hi = f.oracle->bvh().boundsMax(), centre = (lo + hi) * 0.5;
  const double radius = glm::length(hi - lo);
  std::mt19937 rng(28);
  std::normal_distribution<double> n(0.0, 1.0);
  const dvec3 toSun = -dvec3(benchSun().direction);
  while (f.shadowRays.size() < 4096) {
    const dvec3 eye = centre + glm::normalize(dvec3(n(rng), n(rng), n(rng))) * radius;
    const dvec3 dir = glm::normalize(centre + dvec3(n(rng), n(rng), n(rng)) * radius * 0.15 - eye);
    const auto hit = f.oracle->closestHit(eye, dir);
    if (!hit) continue;
    const dvec3 p = eye + dir * hit->t, normal = f.oracle->faceNormal(*hit, dir);
    f.probes.push_back({p, normal});
    f.shadowRays.push_back(Ray{p + normal * f.oracle->epsilon(), toSun, 0.0, 1e300});
  }
  return f;
}

void BM_OracleBvhBuild(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    Bvh bvh(f.triangles);
    benchmark::DoNotOptimize(bvh);
  }
  const BvhStats& s = f.oracle->bvh().stats();
  state.SetLabel(sceneName(static_cast<int>(state.range(0))));
  state.counters["triangles"] = static_cast<double>(s.triangles);
  state.counters["nodes"] = static_cast<double>(s.nodes);
  state.counters["depth"] = s.maxDepth;
  state.counters["sah_cost"] = s.sahCost;
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(s.triangles));
}

// range(0): scene; range(1): 0 BVH, 1 brute force (the BVH's own triangles,
// the same triangle test). One thread; items = shadow rays.
void BM_OracleShadowRays(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  const bool brute = state.range(1) != 0;
  const size_t rays = 1024;  // the same rays for both
  const auto& tris = f.oracle->bvh().triangles();
  size_t blocked = 0;
  for (auto _ : state) {
    blocked = 0;
    for (size_t i = 0; i < rays; ++i) {
      const Ray& r = f.shadowRays[i];
      bool hit = false;
      if (brute) {
        for (const WorldTriangle& t : tris)
          if (intersectTriangle(t, r)) {
            hit = true;
            break;
          }
      } else {
        hit = f.oracle->bvh().anyHit(r);
      }
      blocked += hit;
    }
    benchmark::DoNotOptimize(blocked);
  }
  // The answers must be the same either way: count disagreements on these rays once.
  size_t disagree = 0;
  for (size_t i = 0; i < rays; ++i)
    disagree += f.oracle->bvh().anyHit(f.shadowRays[i]) != bruteForceAnyHit(tris, f.shadowRays[i]);
  state.SetLabel(std::string(sceneName(static_cast<int>(state.range(0)))) + (brute ? " brute force" : " bvh"));
  state.counters["shadowed_share"] = static_cast<double>(blocked) / static_cast<double>(rays);
  state.counters["disagreements"] = static_cast<double>(disagree);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(rays));
}

// The batch form on every hardware thread (VisibilityOracle::classify over probes).
void BM_OracleBatchClassify(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  const DirectionalLight sun = benchSun();
  const int threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    auto answers = f.oracle->classify(f.probes, sun, threads);
    benchmark::DoNotOptimize(answers);
  }
  state.SetLabel(std::string(sceneName(static_cast<int>(state.range(0)))) + " threads " +
                 (threads ? std::to_string(threads) : std::string("all")));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.probes.size()));
}

BENCHMARK(BM_OracleBvhBuild)->ArgNames({"scene"})->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OracleShadowRays)
    ->ArgNames({"scene", "brute"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OracleBatchClassify)
    ->ArgNames({"scene", "threads"})
    ->Args({0, 1})
    ->Args({0, 0})
    ->UseRealTime()  // the work is on other threads: wall time is what a caller waits
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
