// The state of one `rgraph view` session shared by its parts (view_app.cpp:
// window and frame loop; view_input.cpp: mouse and keys).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rgraph/renderer.h"
#include "view_camera.h"

struct GLFWwindow;

namespace rgraph::view {

struct InputState {
  double lastX = 0, lastY = 0;
  bool dragging = false;
  float wheel = 0;         // accumulated by the scroll callback
  bool resetHeld = false;  // R, for edge detection
  bool uiToggleHeld = false;
  // A click: the left button pressed and released within a few pixels, not
  // over a panel. `clicked` holds where (window coordinates, top-left) until
  // the viewer takes it.
  bool leftHeld = false, pressOverUi = false;
  double pressX = 0, pressY = 0;
  bool clicked = false;
  double clickX = 0, clickY = 0;
};

// Applies mouse and keys to the camera (orbit: left drag, look: right drag
// with WASD/QE flying, wheel: zoom, R: reset) unless ImGui wants them; F1 toggles `ui`;
// a left click (no drag) is left in `clicked` for picking.
void handleInput(GLFWwindow* window, InputState& input, CameraController& camera, bool imguiWantsMouse,
                 bool imguiWantsKeyboard, float seconds, bool& ui);

}  // namespace rgraph::view
