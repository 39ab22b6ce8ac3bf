// The one headless GL context every rendering benchmark of rgraph_render_bench
// draws in (GL objects belong to the context that was current when they were
// made, so the benchmarks share it), and the order things go at exit: each
// benchmark's GL objects, then the context, before static destructors.
#pragma once

#include <benchmark/benchmark.h>

#include <exception>
#include <functional>
#include <memory>

namespace rgraph {
class GlContext;
}

namespace rgraph::bench {

// Created and made current on first use.
GlContext& renderContext();
// Called by releaseRenderContext() (in main, after the benchmarks ran) before
// the context is destroyed: drop the GL objects here.
void atContextRelease(std::function<void()> release);
void releaseRenderContext();

// A benchmark file's GL state: `make()` (returning std::unique_ptr<T>) runs
// once, in the shared context, on first use; the object is dropped when the
// context is released. One per T.
template <class T, class Make>
T& contextSingleton(Make make) {
  static std::unique_ptr<T> slot;
  if (!slot) {
    renderContext();
    std::unique_ptr<T> made = make();
    atContextRelease([] { slot.reset(); });
    slot = std::move(made);
  }
  return *slot;
}

// A benchmark's world (`world()`, made on first use), or nullptr after
// SkipWithError with what making it threw (no GL context, a pipeline with
// errors): the benchmark returns at once, the others still run.
template <class World>
World* worldOrSkip(benchmark::State& state, World& (*world)()) {
  try {
    return &world();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

}  // namespace rgraph::bench
