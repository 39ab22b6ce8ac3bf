// The cut-off radius of each light for a lighting pass's threshold: where
// LearnOpenGL's attenuation (chapter 8.2, "Deferred shading": the light
// volume's radius) falls to `threshold`. Light volumes draw spheres and
// cones of this radius; tiled and clustered shading bin lights by it;
// every lighting pass stops a light's contribution at it. Core's light
// buffer holds what these functions give it (GpuScene::bindPointLights).
#pragma once

#include <cstdint>
#include <vector>

namespace rgraph {
class GpuScene;
struct Scene;
}  // namespace rgraph

namespace rgraph::lighting {

// Point and spot lights with radii solved for `threshold` (lightRadius:
// LearnOpenGL's 5/256 of the brightest channel by default) and capped at the
// distance beyond which the scene has no geometry. threshold <= 0: no
// cut-off (radius -1). In scene order.
std::vector<float> cutoffRadii(const Scene& scene, float threshold);
// GpuScene::bindPointLights / pointLightBuffer with cutoffRadii(threshold),
// cached by the threshold: the buffer is written only when the lights
// changed or the threshold was not among the last ones used.
void bindPointLights(GpuScene& scene, float threshold);
uint32_t pointLightBuffer(GpuScene& scene, float threshold);

}  // namespace rgraph::lighting
