// Graph compile time on random DAGs (the description is built outside the
// timed loop). Target: 1,000 passes / 2,000 resources in at most 2 ms.
#include <benchmark/benchmark.h>

#include "../tests/graph/random_graph.h"
#include "rgraph/graph.h"

namespace {

void BM_CompileRandomDag(benchmark::State& state) {
  rgraph::testgen::RandomGraphOptions o;
  o.passes = static_cast<uint32_t>(state.range(0));
  o.resources = static_cast<uint32_t>(state.range(1));
  o.seed = 42;
  o.shuffle = state.range(2) != 0;
  const rgraph::GraphDesc desc = rgraph::testgen::randomGraph(o).desc;
  size_t live = 0, physical = 0;
  for (auto _ : state) {
    rgraph::Plan plan = rgraph::compile(desc);
    live = plan.order.size();
    physical = plan.physical.size();
    benchmark::DoNotOptimize(plan);
  }
  state.counters["live_passes"] = static_cast<double>(live);
  state.counters["physical"] = static_cast<double>(physical);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// Args: passes, resources, shuffled (0: passes declared in a topological
// order, as configs usually are; 1: declared in a random order).
BENCHMARK(BM_CompileRandomDag)
    ->ArgNames({"passes", "resources", "shuffled"})
    ->Args({1000, 2000, 0})
    ->Args({10000, 20000, 0})
    ->Args({1000, 2000, 1})
    ->Args({10000, 20000, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
