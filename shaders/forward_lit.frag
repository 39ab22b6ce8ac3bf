#version 450 core
// Forward shading: every light per fragment, straight from the material (the
// classic forward renderer; also how blended surfaces are lit), or, with
// u_clustered, only the lights of the fragment's cluster (forward+: the lists
// a cluster_lights pass built, include/cluster_shading.glsl). Defines: one
// LIGHTING_*, one ATTENUATION_*, optionally HAS_NORMAL_MAPS, HAS_VELOCITY
// (motion vectors at location 1, as the geometry pass writes them) and the
// shadow defines (include/shadows.glsl: each light times its visibility).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/material_uv.glsl"
#include "include/material.glsl"
#include "include/lighting.glsl"
#include "include/shadows.glsl"
#include "include/clusters.glsl"

#include "include/lights.glsl"
#include "include/cluster_shading.glsl"
uniform int u_pointLightCount;
uniform int u_clustered;  // 1: the cluster lists are on storage buffer 1
uniform int u_blendPass;  // 1: blended surfaces (alpha kept), 0: opaque (alpha 1)
layout(location = 0) out vec4 outColor;
#if defined(HAS_VELOCITY)
layout(location = 1) out vec2 outVelocity;
in vec4 vs_clipNow;
in vec4 vs_clipPrev;
#endif

void main() {
  vec3 V = safeNormal(u_cameraPos.xyz - fs.worldPos, vec3(0.0, 0.0, 1.0));
  float alpha;
  bool discarded;
  Surface s = materialSurface(V, alpha, discarded);
  if (discarded) discard;
#if defined(HAS_VELOCITY)
  outVelocity = screenVelocity(vs_clipNow, vs_clipPrev);
#endif
  vec3 color = ambientTerm(s, V) + shadeDirectionalLight(s, V) * sunVisibility(s);
  if (u_clustered != 0) {
    const float viewDepth = max(-(u_view * vec4(fs.worldPos, 1.0)).z, 0.0);
    color += shadeClusterLights(ivec2(gl_FragCoord.xy), viewDepth, u_pointLightCount, s, V);
  } else {
    for (int i = 0; i < u_pointLightCount; ++i) color += shadePointLight(lights[i], s, V) * lightVisibility(i, s);
  }
  color += emissiveTerm(s);
  outColor = vec4(color, u_blendPass != 0 ? alpha : 1.0);
}
