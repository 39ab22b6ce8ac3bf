// How many of a posed scene's deformed vertices (deformPrimitive, the CPU
// reference) lie outside their primitive's bounds: what culling and shadow
// fitting must never miss. Header-only (no GL): the scene tests and the GPU
// animation tests share it.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "rgraph/animation.h"
#include "rgraph/scene.h"

namespace rgraph::testsupport {

// Each box gets a slack of 1e-4 of its coordinates' size (float rounding of
// the transformed corners), plus 1e-6.
inline size_t verticesOutsideBounds(const Scene& s, const Pose& pose) {
  size_t outside = 0;
  for (size_t i = 0; i < s.primitives.size(); ++i) {
    const Bounds& b = s.primitives[i].bounds;
    const glm::vec3 slack = 1e-4f * glm::max(glm::abs(b.min), glm::abs(b.max)) + 1e-6f;
    for (const glm::vec3& p : deformPrimitive(s, pose, i).positions)
      outside += glm::any(glm::lessThan(p, b.min - slack)) || glm::any(glm::greaterThan(p, b.max + slack));
  }
  return outside;
}

}  // namespace rgraph::testsupport
