// How the resource inspector turns a texel into a displayed colour. These
// pure functions are the reference the inspector's display shader mirrors
// line by line (view_panels_inspector.cpp, kDisplayFrag): tested on the CPU.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace rgraph::view {

struct ValueMapping {
  enum class Channel { rgba, r, g, b, a };
  // raw: the stored values; depth: window depth -> linear distance mapped so
  // near = 0, far = 1; normal: [-1,1] -> [0,1]; position: the scene bounds -> [0,1].
  enum class Mode { raw, depth, normal, position };
  Channel channel = Channel::rgba;
  Mode mode = Mode::raw;
  float min = 0.0f, max = 1.0f;  // range remap after the mode (min -> 0, max -> 1)
  bool log = false;              // remap log2 of the values (and of min, max) instead
  float near = 0.1f, far = 100.0f;
  glm::vec3 boundsMin{-1.0f}, boundsMax{1.0f};
};

// Eye-space distance of a window depth in [0,1] written with a GL
// perspective projection (-1..1 clip depth) of these planes.
float linearizeDepth(float depth, float near, float far);
// The displayed colour (each component in [0,1], alpha 1 unless the channel is rgba).
glm::vec4 mapValue(const ValueMapping& m, glm::vec4 texel);
// The smallest and largest value of RGBA texels (x = min, y = max): colour
// over R, G and B; depth (`depth`) over R without the texels at 1, a depth
// map's clear where nothing was drawn. (0, 1) when no texel counts.
glm::vec2 valueRange(const std::vector<float>& rgba, bool depth);

}  // namespace rgraph::view
