// Fixed-function state set in one go: the items of rgraph/renderer.h's GL
// state contract that a pass must set itself (or that the executor resets),
// one value each. One setter for the two places that set them all: the
// executor's hostile state before each pass (hazard mode state-scramble,
// executor_hazards.cpp) and the test support's caller, which leaves its own
// state set around a frame (tests/support/caller_drawing.cpp). Not installed.
#pragma once

#include <array>
#include <cstdint>

namespace rgraph::gl {

struct FixedState {
  bool blend = false;
  uint32_t blendSrcRgb = 0, blendDstRgb = 0, blendSrcAlpha = 0, blendDstAlpha = 0;  // GL enums
  uint32_t blendEquationRgb = 0, blendEquationAlpha = 0;
  std::array<float, 4> blendColor{};
  bool depthTest = false;
  uint32_t depthFunc = 0;
  bool depthMask = true;
  bool stencilTest = false;
  uint32_t stencilFunc = 0;  // front and back
  int32_t stencilRef = 0;
  uint32_t stencilValueMask = 0;
  uint32_t stencilFail = 0, stencilDepthFail = 0, stencilPass = 0;
  uint32_t stencilWriteMask = 0;
  bool cullFace = false;
  uint32_t cullMode = 0, frontFace = 0;
  bool scissorTest = false;
  std::array<int32_t, 4> scissor{}, viewport{};  // x, y, width, height (every index)
  std::array<bool, 4> colorMask{true, true, true, true};  // every draw buffer
  bool framebufferSrgb = false;
};

// Sets every item (needs a current GL context).
void applyFixedState(const FixedState& s);

// What state-scramble sets before each pass: additive blending with reverse
// subtract, depth and stencil tests that never pass and write nothing, both
// faces culled with clockwise fronts, a 1x1 scissor box, a 7x9 viewport at
// (3,5), red and blue masked, framebuffer sRGB off.
const FixedState& hostileFixedState();

}  // namespace rgraph::gl
