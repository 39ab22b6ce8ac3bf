#version 450 core
// One instance per point light: the unit icosphere scaled to enclose the
// light's radius (u_volumeScale makes its flat faces reach the sphere).
#include "include/frame.glsl"

layout(location = 0) in vec3 a_position;
layout(std430, binding = 0) readonly buffer Lights { PointLight lights[]; };
uniform float u_volumeScale;

flat out int v_light;

void main() {
  PointLight l = lights[gl_InstanceID];
  float r = max(l.positionRadius.w, 0.0) * u_volumeScale;
  v_light = gl_InstanceID;
  gl_Position = u_viewProj * vec4(l.positionRadius.xyz + a_position * r, 1.0);
}
