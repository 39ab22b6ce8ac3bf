// Mouse and keyboard for rgraph view (view_app.h).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>

#include "view_app.h"

namespace rgraph::view {

void handleInput(GLFWwindow* window, InputState& in, CameraController& camera, bool imguiWantsMouse,
                 bool imguiWantsKeyboard, float seconds, bool& ui) {
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  const float dx = float(x - in.lastX), dy = float(y - in.lastY);
  in.lastX = x;
  in.lastY = y;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  // A drag that starts over a panel belongs to the panel until released.
  if (!left && !right)
    in.dragging = false;
  else if (!in.dragging && !imguiWantsMouse)
    in.dragging = true;
  // A click selects (picking): released within 3 pixels of where it was pressed.
  if (left && !in.leftHeld) {
    in.pressX = x, in.pressY = y;
    in.pressOverUi = imguiWantsMouse;
  }
  if (!left && in.leftHeld && !in.pressOverUi && std::abs(x - in.pressX) <= 3 && std::abs(y - in.pressY) <= 3) {
    in.clicked = true;
    in.clickX = x, in.clickY = y;
  }
  in.leftHeld = left;
  if (in.dragging && left) camera.orbit(dx, dy);
  if (in.dragging && right) camera.look(dx, dy);
  if (!imguiWantsMouse && in.wheel != 0) camera.zoom(in.wheel);
  in.wheel = 0;

  const bool f1 = glfwGetKey(window, GLFW_KEY_F1) == GLFW_PRESS;
  if (f1 && !in.uiToggleHeld) ui = !ui;
  in.uiToggleHeld = f1;
  if (imguiWantsKeyboard) return;
  auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
  const bool r = key(GLFW_KEY_R) > 0;
  if (r && !in.resetHeld) camera.reset();
  in.resetHeld = r;
  // Speed scales with the distance to the target so that small and large scenes both fly.
  const float speed = 0.5f * glm::length(camera.camera().target - camera.camera().position) * seconds;
  const float right_ = key(GLFW_KEY_D) - key(GLFW_KEY_A), up = key(GLFW_KEY_E) - key(GLFW_KEY_Q),
              forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
  if (right_ != 0 || up != 0 || forward != 0) camera.move(right_ * speed, up * speed, forward * speed);
}

}  // namespace rgraph::view
