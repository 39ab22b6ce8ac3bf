// The inspector's value mapping on the CPU (see view_panels_map.h).
#include "view_panels_map.h"

#include <algorithm>
#include <cmath>

namespace rgraph::view {

float linearizeDepth(float depth, float near, float far) {
  const float ndc = depth * 2.0f - 1.0f;
  return 2.0f * near * far / (far + near - ndc * (far - near));
}

namespace {
// log2 with the values at or below zero held at a small positive floor, so
// that a log remap of a range starting at 0 stays finite.
float safeLog(float v) { return std::log2(std::max(v, 1e-6f)); }
}  // namespace

glm::vec4 mapValue(const ValueMapping& m, glm::vec4 v) {
  using Mode = ValueMapping::Mode;
  if (m.mode == Mode::depth) {
    const float lin = (linearizeDepth(v.r, m.near, m.far) - m.near) / (m.far - m.near);
    v = glm::vec4(lin, lin, lin, 1.0f);
  } else if (m.mode == Mode::normal) {
    v = glm::vec4(glm::vec3(v) * 0.5f + 0.5f, v.a);
  } else if (m.mode == Mode::position) {
    const glm::vec3 extent = glm::max(m.boundsMax - m.boundsMin, glm::vec3(1e-6f));
    v = glm::vec4((glm::vec3(v) - m.boundsMin) / extent, v.a);
  }
  float lo = m.min, hi = m.max;
  if (m.log) {
    v = glm::vec4(safeLog(v.r), safeLog(v.g), safeLog(v.b), safeLog(v.a));
    lo = safeLog(lo);
    hi = safeLog(hi);
  }
  const float span = std::abs(hi - lo) < 1e-12f ? 1e-12f : hi - lo;
  v = glm::clamp((v - lo) / span, 0.0f, 1.0f);
  switch (m.channel) {
    case ValueMapping::Channel::rgba:
      return v;
    case ValueMapping::Channel::r:
      return glm::vec4(glm::vec3(v.r), 1.0f);
    case ValueMapping::Channel::g:
      return glm::vec4(glm::vec3(v.g), 1.0f);
    case ValueMapping::Channel::b:
      return glm::vec4(glm::vec3(v.b), 1.0f);
    case ValueMapping::Channel::a:
      return glm::vec4(glm::vec3(v.a), 1.0f);
  }
  return v;
}

glm::vec2 valueRange(const std::vector<float>& rgba, bool depth) {
  float lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4)
    for (size_t c = 0; c < (depth ? 1u : 3u); ++c) {
      const float v = rgba[i + c];
      if (!std::isfinite(v) || (depth && v >= 1.0f)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  return lo <= hi ? glm::vec2(lo, hi) : glm::vec2(0.0f, 1.0f);
}

}  // namespace rgraph::view
