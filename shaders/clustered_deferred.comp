#version 450 core
// Clustered shading, step 2: every pixel finds its cluster (its tile and the
// depth slice of its view depth, include/clusters.glsl) and shades ambient,
// the directional light and the lights clustered_build.comp listed there,
// storing the HDR result (include/cluster_shading.glsl, as forward+ does;
// overflowing clusters are handled there).
// The maths is include/lighting.glsl's, as in deferred_lighting.frag and
// tiled_deferred.comp, so the methods agree.
// With FAR_FIELD the listed lights are shaded without their cut and the
// cluster's far field (the lights it does not list, clustered_far.comp)
// is added (include/cluster_far_field.glsl), not shadowed.
// Defines: one GBUFFER_*, one LIGHTING_*, one ATTENUATION_*, the shadow ones
// (include/shadows.glsl); TARGET_FORMAT
// (rgba16f, rgba32f or r11f_g11f_b10f); FAR_FIELD. The grid is the list buffer's.
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#include "include/shadows.glsl"
#include "include/clusters.glsl"
#if defined(FAR_FIELD)
#include "include/far_field.glsl"
#include "include/cluster_far_field.glsl"
#endif

#ifndef TARGET_FORMAT
#define TARGET_FORMAT rgba16f
#endif

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "include/invocation.glsl"

#include "include/lights.glsl"
#include "include/cluster_shading.glsl"
layout(TARGET_FORMAT, binding = 0) uniform image2D u_target;
uniform int u_pointLightCount;
uniform int u_ambientAndSun;  // 1: add ambient and the directional light
uniform int u_load;           // 1: add to what the target holds

void main() {
  // One pixel an invocation, nothing shared: no assumption about the others.
  const ivec2 px = ivec2(globalId().xy);
  if (px.x >= int(u_viewport.x) || px.y >= int(u_viewport.y)) return;
  const Surface s = readSurface(px);
  if (!s.covered) return;  // the target's clear value (background) stays
  const vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  vec3 color = vec3(0.0);
  if (u_load != 0) color = imageLoad(u_target, px).rgb;
  if (u_ambientAndSun != 0) color += ambientTerm(s, V) + shadeDirectionalLight(s, V) * sunVisibility(s);
  const float viewDepth = max(-(u_view * vec4(s.position, 1.0)).z, 0.0);
  color += shadeClusterLights(px, viewDepth, u_pointLightCount, s, V);
#if defined(FAR_FIELD)
  if (u_pointLightCount > 0 && clusterListsFit(uint(data.length())))
    color += shadeClusterFarField(clusterAt(px, viewDepth), s, V);
#endif
  if (u_ambientAndSun != 0) color += emissiveTerm(s);  // once per pixel: with the ambient
  imageStore(u_target, px, vec4(color, 1.0));
}
