// The one headless GL context every rendering benchmark of rgraph_render_bench
// draws in (GL objects belong to the context that was current when they were
// made, so the benchmarks share it), and the order things go at exit: each
// benchmark's GL objects, then the context, before static destructors.
#pragma once

#include <functional>

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

}  // namespace rgraph::bench
