// The viewer's camera controls, GL- and window-free: orbit about the target,
// fly (move and look), zoom toward the target, reset to the scene's camera.
#pragma once

#include <string>

#include "rgraph/scene.h"

namespace rgraph::view {

class CameraController {
 public:
  // Sets the pose and remembers it as the one reset() returns to.
  void setHome(const Camera& camera);
  void reset() { camera_ = home_; }
  void set(const Camera& camera) { camera_ = camera; }
  const Camera& camera() const { return camera_; }

  // Orbit the position about the target by mouse motion in pixels (yaw about +Y, pitch clamped short of the poles).
  void orbit(float dxPixels, float dyPixels);
  // Turn the view direction about the position (fly mode's look), target kept at the same distance.
  void look(float dxPixels, float dyPixels);
  // Move position and target together: x right, y up, z forward, in world units.
  void move(float right, float up, float forward);
  // Wheel steps: positive moves toward the target (never past it).
  void zoom(float steps);

  // "px,py,pz,tx,ty,tz,fov": what `rgraph render --camera` takes.
  std::string cameraArgument() const;

 private:
  Camera home_, camera_;
};

}  // namespace rgraph::view
