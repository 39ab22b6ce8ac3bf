// The lights buffer (std430, binding 0): the scene's point lights first, then
// its spot lights (PointLight in include/frame.glsl; include that first),
// bound by the passes with GpuScene::bindPointLights. Declared here once for
// every shader that reads the lights.
layout(std430, binding = 0) readonly buffer Lights { PointLight lights[]; };
