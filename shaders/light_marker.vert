#version 450 core
// A small cube at each point light (LearnOpenGL's light boxes).
#include "include/frame.glsl"

layout(location = 0) in vec3 a_position;
#include "include/lights.glsl"
uniform float u_markerSize;  // half extent
flat out vec3 v_color;

void main() {
  PointLight l = lights[gl_InstanceID];
  v_color = l.color.rgb;
  gl_Position = u_viewProj * vec4(l.positionRadius.xyz + a_position * u_markerSize, 1.0);
}
