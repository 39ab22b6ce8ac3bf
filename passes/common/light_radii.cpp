#include "rgraph/passes/light_radii.h"

#include <algorithm>
#include <cmath>

#include "rgraph/gl/gpu_scene.h"
#include "rgraph/scene.h"

namespace rgraph::lighting {

std::vector<float> cutoffRadii(const Scene& scene, float threshold) {
  const Bounds bounds = scene.bounds();
  std::vector<float> radii;
  radii.reserve(scene.pointLights.size());
  for (const auto& l : scene.pointLights) {
    if (threshold <= 0.0f) {
      radii.push_back(-1.0f);
      continue;
    }
    float r = lightRadius(l, threshold);
    // Nothing lies farther than this, so a bigger volume only costs fill rate
    // (and an infinite one, for a light with no falloff, cannot be drawn).
    if (!bounds.empty()) r = std::min(r, glm::length(l.position - bounds.center()) + bounds.radius());
    if (!std::isfinite(r)) r = 0.0f;
    radii.push_back(std::max(r, 0.0f));
  }
  return radii;
}

void bindPointLights(GpuScene& scene, float threshold) {
  scene.bindPointLights(threshold, [&scene, threshold] { return cutoffRadii(scene.scene(), threshold); });
}

uint32_t pointLightBuffer(GpuScene& scene, float threshold) {
  return scene.pointLightBuffer(threshold, [&scene, threshold] { return cutoffRadii(scene.scene(), threshold); });
}

}  // namespace rgraph::lighting
