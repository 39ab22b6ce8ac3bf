// Camera controls (view_camera.h).
#include "view_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>

namespace rgraph::view {
namespace {

constexpr float kRadiansPerPixel = 0.005f;
constexpr float kZoomPerStep = 0.9f;
constexpr float kMinDistance = 1e-3f;
constexpr float kMaxPitch = glm::half_pi<float>() - 0.01f;

// Rotates offset d (from a centre) by yaw about +Y and pitch about the horizontal axis, pitch clamped.
glm::vec3 rotate(glm::vec3 d, float yaw, float pitch) {
  const float r = glm::length(d);
  if (r < kMinDistance) return d;
  float az = std::atan2(d.x, d.z) + yaw;
  float el = std::asin(std::clamp(d.y / r, -1.0f, 1.0f)) + pitch;
  el = std::clamp(el, -kMaxPitch, kMaxPitch);
  return r * glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
}

}  // namespace

void CameraController::setHome(const Camera& camera) { home_ = camera_ = camera; }

void CameraController::orbit(float dx, float dy) {
  camera_.position =
      camera_.target + rotate(camera_.position - camera_.target, -dx * kRadiansPerPixel, dy * kRadiansPerPixel);
}

void CameraController::look(float dx, float dy) {
  camera_.target =
      camera_.position + rotate(camera_.target - camera_.position, -dx * kRadiansPerPixel, -dy * kRadiansPerPixel);
}

void CameraController::move(float right, float up, float forward) {
  const glm::vec3 f = camera_.forward();
  glm::vec3 r = glm::cross(f, glm::vec3(0, 1, 0));
  r = glm::length(r) > 1e-6f ? glm::normalize(r) : glm::vec3(1, 0, 0);
  const glm::vec3 delta = r * right + glm::vec3(0, 1, 0) * up + f * forward;
  camera_.position += delta;
  camera_.target += delta;
}

void CameraController::zoom(float steps) {
  const glm::vec3 d = camera_.position - camera_.target;
  const float r = std::max(glm::length(d) * std::pow(kZoomPerStep, steps), kMinDistance);
  if (glm::length(d) > 0) camera_.position = camera_.target + glm::normalize(d) * r;
}

std::string CameraController::cameraArgument() const {
  const Camera& c = camera_;
  char text[256];
  std::snprintf(text, sizeof text, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", c.position.x, c.position.y, c.position.z,
                c.target.x, c.target.y, c.target.z, c.fovY);
  return text;
}

}  // namespace rgraph::view
