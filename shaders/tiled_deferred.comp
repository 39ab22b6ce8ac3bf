#version 450 core
// Tiled deferred lighting: one work group per TILE_SIZE x TILE_SIZE tile of
// the G-buffer. (1) Every invocation reads its pixel's surface and the group
// reduces the tile's view-depth bounds; (2) the group culls every point light
// against the tile's frustum (four side planes through the eye, and the depth
// bounds) into a shared list; (3) every pixel shades ambient, the directional
// light and the lights in its tile's list, and stores the HDR result.
// The maths is include/lighting.glsl's, as in deferred_lighting.frag and
// light_volume.frag, so the methods agree.
// Defines: one GBUFFER_*, one LIGHTING_*, one ATTENUATION_*; TILE_SIZE,
// MAX_TILE_LIGHTS (bounded by GL_MAX_COMPUTE_SHARED_MEMORY_SIZE), TARGET_FORMAT
// (the image format qualifier of the target: rgba16f or rgba32f).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"

#ifndef TILE_SIZE
#define TILE_SIZE 16
#endif
#ifndef MAX_TILE_LIGHTS
#define MAX_TILE_LIGHTS 1024
#endif
#ifndef TARGET_FORMAT
#define TARGET_FORMAT rgba16f
#endif

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE, local_size_z = 1) in;

layout(std430, binding = 0) readonly buffer Lights { PointLight lights[]; };
layout(TARGET_FORMAT, binding = 0) uniform image2D u_target;
uniform int u_pointLightCount;
uniform int u_ambientAndSun;  // 1: add ambient and the directional light
uniform int u_load;           // 1: add to what the target holds (e.g. an ambient pass's output)

shared uint s_minDepth;  // floatBitsToUint of the positive view depth (orders like the float)
shared uint s_maxDepth;
shared uint s_count;
shared uint s_lights[MAX_TILE_LIGHTS];

void main() {
  const ivec2 size = ivec2(u_viewport.xy);
  const ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  const uint local = gl_LocalInvocationIndex;
  const bool inside = px.x < size.x && px.y < size.y;

  if (local == 0u) {
    s_minDepth = 0x7f7fffffu;
    s_maxDepth = 0u;
    s_count = 0u;
  }
  barrier();

  Surface s;
  s.covered = false;
  float viewDepth = 0.0;
  if (inside) {
    s = readSurface(px);
    if (s.covered) {
      viewDepth = max(-(u_view * vec4(s.position, 1.0)).z, 0.0);
      atomicMin(s_minDepth, floatBitsToUint(viewDepth));
      atomicMax(s_maxDepth, floatBitsToUint(viewDepth));
    }
  }
  barrier();

  const bool tileCovered = s_maxDepth != 0u || s_minDepth != 0x7f7fffffu;
  if (tileCovered && u_pointLightCount > 0) {
    const float minDepth = uintBitsToFloat(s_minDepth);
    const float maxDepth = uintBitsToFloat(s_maxDepth);
    // The tile's edges in NDC, and the planes through the eye that bound it
    // (view space; clip.x = P00 x + P20 z, clip.w = -z).
    const vec2 tileMin = vec2(gl_WorkGroupID.xy * uvec2(TILE_SIZE));
    const vec2 tileMax = min(tileMin + vec2(TILE_SIZE), vec2(size));
    const vec2 ndc0 = tileMin * u_viewport.zw * 2.0 - 1.0;
    const vec2 ndc1 = tileMax * u_viewport.zw * 2.0 - 1.0;
    const float p00 = u_proj[0][0], p11 = u_proj[1][1], p20 = u_proj[2][0], p21 = u_proj[2][1];
    vec3 planes[4];
    planes[0] = vec3(p00, 0.0, p20 + ndc0.x);      // x >= left
    planes[1] = vec3(-p00, 0.0, -(p20 + ndc1.x));  // x <= right
    planes[2] = vec3(0.0, p11, p21 + ndc0.y);      // y >= bottom
    planes[3] = vec3(0.0, -p11, -(p21 + ndc1.y));  // y <= top
    for (int i = 0; i < 4; ++i) planes[i] = normalize(planes[i]);

    for (uint i = local; i < uint(u_pointLightCount); i += uint(TILE_SIZE * TILE_SIZE)) {
      const vec4 pr = lights[i].positionRadius;
      bool visible = true;
      if (pr.w >= 0.0) {
        // A little slack so rounding never drops a light a pixel can see.
        const float r = pr.w * 1.001 + 1e-4;
        const vec3 c = (u_view * vec4(pr.xyz, 1.0)).xyz;
        const float depth = -c.z;
        visible = depth + r >= minDepth && depth - r <= maxDepth;
        for (int p = 0; p < 4 && visible; ++p) visible = dot(planes[p], c) >= -r;
      }
      if (visible) {
        const uint slot = atomicAdd(s_count, 1u);
        if (slot < uint(MAX_TILE_LIGHTS)) s_lights[slot] = i;
      }
    }
  }
  barrier();

  if (!inside || !s.covered) return;  // the target's clear value (background) stays
  const vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  vec3 color = vec3(0.0);
  if (u_load != 0) color = imageLoad(u_target, px).rgb;
  if (u_ambientAndSun != 0) color += ambientTerm(s) + shadeDirectionalLight(s, V);
  const uint count = s_count;
  if (count <= uint(MAX_TILE_LIGHTS)) {
    for (uint i = 0u; i < count; ++i) color += shadePointLight(lights[s_lights[i]], s, V);
  } else {
    // More lights reach this tile than the list holds: shade them all (correct, slow).
    for (int i = 0; i < u_pointLightCount; ++i) color += shadePointLight(lights[i], s, V);
  }
  imageStore(u_target, px, vec4(color, 1.0));
}
