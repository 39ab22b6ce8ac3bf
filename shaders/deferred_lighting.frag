#version 450 core
// Deferred lighting, once per pixel: ambient + the directional light + every
// point light (unless light volumes draw those). Defines: one GBUFFER_*, one
// LIGHTING_*, one ATTENUATION_*, optionally LIGHT_RADIUS_BRANCH and the
// shadow defines (include/shadows.glsl).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#include "include/shadows.glsl"

#include "include/lights.glsl"
uniform int u_pointLightCount;  // 0 when another pass lights the point lights
uniform int u_ambientAndSun;    // 1: add ambient and the directional light
uniform int u_hasAo;            // 1: u_ao (r, any size) scales the ambient term
layout(binding = 5) uniform sampler2D u_ao;

layout(location = 0) out vec4 outColor;

void main() {
  Surface s = readSurface(ivec2(gl_FragCoord.xy));
  if (!s.covered) discard;  // the target's clear value (background) stays
  vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  vec3 color = vec3(0.0);
  if (u_ambientAndSun != 0) {
    float occlusion = u_hasAo != 0 ? texture(u_ao, gl_FragCoord.xy * u_viewport.zw).r : 1.0;
    color += ambientTerm(s, V) * occlusion + shadeDirectionalLight(s, V) * sunVisibility(s);
  }
  for (int i = 0; i < u_pointLightCount; ++i) color += shadePointLight(lights[i], s, V) * lightVisibility(i, s);
  if (u_ambientAndSun != 0) color += emissiveTerm(s);  // once per pixel: with the ambient
  outColor = vec4(color, 1.0);
}
