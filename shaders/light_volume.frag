#version 450 core
// Shades one light at the pixels its volume covers; blended additively.
// Defines: one GBUFFER_*, LIGHTING_*, ATTENUATION_*; the shadow ones (include/shadows.glsl).
// No discard: a shader that may discard makes the rasteriser run it before
// the depth test (llvmpipe: 2-3x the fragments shaded); adding 0 is the same.
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#include "include/shadows.glsl"

#include "include/lights.glsl"
flat in int v_light;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = vec4(0.0);
  Surface s = readSurface(ivec2(gl_FragCoord.xy));
  if (!s.covered) return;
  PointLight light = lights[v_light];
  // The mesh encloses the sphere, and its far side also lies behind surfaces
  // in front of the light: pixels out of the light's reach get exactly 0.
  if (distance(light.positionRadius.xyz, s.position) > light.positionRadius.w) return;
  vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  outColor = vec4(shadePointLight(light, s, V) * lightVisibility(v_light, s), 0.0);
}
