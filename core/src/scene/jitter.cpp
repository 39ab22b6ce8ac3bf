#include "rgraph/jitter.h"

namespace rgraph {

float halton(uint32_t index, uint32_t base) {
  if (base < 2) return 0.0f;
  double f = 1.0, r = 0.0;
  for (uint32_t i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return static_cast<float>(r);
}

glm::vec2 jitterPixels(uint64_t frame, uint32_t phases) {
  if (phases == 0) return glm::vec2(0.0f);
  const auto k = static_cast<uint32_t>(frame % phases) + 1;
  return {halton(k, 2) - 0.5f, halton(k, 3) - 0.5f};
}

}  // namespace rgraph
