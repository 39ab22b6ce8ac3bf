#version 450 core
// Shades one light at the pixels its volume covers; blended additively.
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"

layout(std430, binding = 0) readonly buffer Lights { PointLight lights[]; };
flat in int v_light;
layout(location = 0) out vec4 outColor;

void main() {
  Surface s = readSurface(ivec2(gl_FragCoord.xy));
  if (!s.covered) discard;
  vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  outColor = vec4(shadePointLight(lights[v_light], s, V), 0.0);
}
