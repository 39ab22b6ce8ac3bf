// Model animation (Primitive::transformAt): GL-free so tests can check the
// matrices the renderer uses against their own maths.
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/scene.h"

namespace rgraph {

glm::mat4 Primitive::transformAt(double seconds) const {
  if (!animated()) return transform;
  // The angle in double, wrapped to one turn before it becomes a float, so
  // that hours of animation keep sub-pixel precision.
  const double degrees = std::fmod(double(spin.degreesPerSecond) * seconds, 360.0);
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(float(degrees)), spin.axis);
  return glm::translate(glm::mat4(1.0f), spin.pivot) * turn * glm::translate(glm::mat4(1.0f), -spin.pivot) * transform;
}

}  // namespace rgraph
