// Sub-pixel camera jitter for temporal anti-aliasing: a pipeline that turns
// it on ("jitter": N in its config) moves the projection by a different
// sub-pixel offset each frame, from the Halton(2,3) low-discrepancy sequence,
// so that a temporal filter accumulates N distinct samples per pixel.
// GL-free.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

namespace rgraph {

// The radical inverse of `index` (>= 1) in `base` (>= 2): a value in (0, 1).
float halton(uint32_t index, uint32_t base);

// The jitter of frame `frame` with `phases` phases, in pixels, each component
// in (-0.5, 0.5): (halton(k, 2) - 0.5, halton(k, 3) - 0.5) with
// k = frame % phases + 1. phases == 0: no jitter (0, 0).
glm::vec2 jitterPixels(uint64_t frame, uint32_t phases);

}  // namespace rgraph
