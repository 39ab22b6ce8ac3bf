#version 450 core
// Tiled deferred lighting: one work group per TILE_SIZE x TILE_SIZE tile of
// the G-buffer. (1) Every invocation reads its pixel's surface and the group
// reduces the view-depth bounds of the tile and of its four quarters, and
// marks which of 32 slices of the tile's depth range hold pixels; (2) the
// group culls every point light against the tile (the occupied depth slices,
// then the sphere against the box bounding the tile's frustum over the
// light's depth range) into a shared list; (3) it refines that list into one
// list per quarter, against each quarter's box; (4) every pixel shades
// ambient, the directional light and the lights in its quarter's list, and
// stores the HDR result.
// Why quarters: in the many-lights scene the field grows with the light
// count, so a tile covers more of the world at 1,024 lights than at 64 and
// its list holds ~3x the lights any one pixel is reached by; the quarter
// lists cut the shading loop near the per-pixel count while the culling loop
// over all N lights stays per tile.
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
shared uint s_depthMask;  // 2.5D culling: bit b set when a pixel's depth falls in slice b of [min, max]
shared uint s_lights[MAX_TILE_LIGHTS];
shared uint s_quarterMin[4], s_quarterMax[4], s_quarterCount[4];
shared uint s_quarterLights[4][MAX_TILE_LIGHTS];  // each a subset of s_lights: never overflows

const uint kHalf = uint(TILE_SIZE) / 2u;

// The slice (0..31) of [minDepth, minDepth + 32 / scale] a view depth falls in.
// Pixels and lights use this one function, so that, floor being monotonic, a
// light spanning depths [a, b] spans the slices of every depth between them.
int depthSlice(float depth, float minDepth, float scale) {
  return clamp(int(floor((depth - minDepth) * scale)), 0, 31);
}

// A light's radius with a little slack, so that rounding never drops a light
// a pixel can see.
float slackRadius(float radius) { return radius * 1.001 + 1e-4; }

// Where the pixel rectangle [pxMin, pxMax) (clamped to the viewport) is in
// view space per unit of depth: a point at view depth d is inside its
// frustum when x / d lies in [perDepth0.x, perDepth1.x] (and y likewise),
// since ndc.x = (P00 x + P20 z) / -z with z = -d.
void frustumPerDepth(uvec2 pxMin, uvec2 pxMax, out vec2 perDepth0, out vec2 perDepth1) {
  const vec2 ndc0 = vec2(pxMin) * u_viewport.zw * 2.0 - 1.0;
  const vec2 ndc1 = min(vec2(pxMax), u_viewport.xy) * u_viewport.zw * 2.0 - 1.0;
  const vec2 p = vec2(u_proj[0][0], u_proj[1][1]), pz = vec2(u_proj[2][0], u_proj[2][1]);
  perDepth0 = (ndc0 + pz) / p;
  perDepth1 = (ndc1 + pz) / p;
}

// Whether a sphere (centre: view x, y and depth) meets the box bounding the
// frustum between depths [minDepth, maxDepth] clipped to the sphere's own
// depth range. The frustum's sides are linear in depth, so the box's extremes
// are at the clipped range's ends; clipping first keeps the box small. It is
// tight for lights small against the tile, which sphere-against-plane tests
// pass near the tile's corners. Conservative: any point of the frustum slice
// within the sphere is in the box.
bool sphereMeetsFrustumBox(vec3 c, float r, float minDepth, float maxDepth, vec2 perDepth0, vec2 perDepth1) {
  const float z0 = max(c.z - r, minDepth), z1 = min(c.z + r, maxDepth);
  if (z0 > z1) return false;
  const vec2 boxMin = min(perDepth0 * z0, perDepth0 * z1), boxMax = max(perDepth1 * z0, perDepth1 * z1);
  const vec2 dxy = max(max(boxMin - c.xy, c.xy - boxMax), vec2(0.0));
  const float dz = max(max(z0 - c.z, c.z - z1), 0.0);
  return dot(dxy, dxy) + dz * dz <= r * r;
}

void main() {
  const ivec2 size = ivec2(u_viewport.xy);
  const ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  const uint local = gl_LocalInvocationIndex;
  const bool inside = px.x < size.x && px.y < size.y;
  const uint quarter = (gl_LocalInvocationID.x >= kHalf ? 1u : 0u) + (gl_LocalInvocationID.y >= kHalf ? 2u : 0u);

  if (local == 0u) {
    s_minDepth = 0x7f7fffffu;
    s_maxDepth = 0u;
    s_count = 0u;
    s_depthMask = 0u;
  }
  if (local < 4u) {
    s_quarterMin[local] = 0x7f7fffffu;
    s_quarterMax[local] = 0u;
    s_quarterCount[local] = 0u;
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
      atomicMin(s_quarterMin[quarter], floatBitsToUint(viewDepth));
      atomicMax(s_quarterMax[quarter], floatBitsToUint(viewDepth));
    }
  }
  barrier();

  const bool tileCovered = s_maxDepth != 0u || s_minDepth != 0x7f7fffffu;
  const float minDepth = uintBitsToFloat(s_minDepth);
  const float maxDepth = uintBitsToFloat(s_maxDepth);
  // Slices of the tile's depth range that hold pixels: a tile over a depth
  // discontinuity (a near object in front of a far one) then rejects the
  // lights in the empty gap between them, which the depth bounds keep.
  const float sliceScale = 32.0 / max(maxDepth - minDepth, 1e-6);
  if (inside && s.covered) atomicOr(s_depthMask, 1u << uint(depthSlice(viewDepth, minDepth, sliceScale)));
  barrier();

  if (tileCovered && u_pointLightCount > 0) {
    const uvec2 tileMin = gl_WorkGroupID.xy * uvec2(TILE_SIZE);
    vec2 perDepth0, perDepth1;
    frustumPerDepth(tileMin, tileMin + uvec2(TILE_SIZE), perDepth0, perDepth1);
    const uint mask = s_depthMask;
    const vec4 viewRowZ = vec4(u_view[0][2], u_view[1][2], u_view[2][2], u_view[3][2]);
    for (uint i = local; i < uint(u_pointLightCount); i += uint(TILE_SIZE * TILE_SIZE)) {
      const vec4 pr = lights[i].positionRadius;
      bool visible = true;
      if (pr.w >= 0.0) {
        const float r = slackRadius(pr.w);
        // The depth test first: it needs only the view matrix's z row.
        const float depth = -dot(viewRowZ, vec4(pr.xyz, 1.0));
        const float z0 = max(depth - r, minDepth), z1 = min(depth + r, maxDepth);
        visible = z0 <= z1;
        if (visible) {
          const int lo = depthSlice(z0, minDepth, sliceScale), hi = depthSlice(z1, minDepth, sliceScale);
          visible = (mask & ((0xffffffffu >> uint(31 - hi)) & (0xffffffffu << uint(lo)))) != 0u;
        }
        if (visible)
          visible = sphereMeetsFrustumBox(vec3((u_view * vec4(pr.xyz, 1.0)).xy, depth), r, minDepth, maxDepth,
                                          perDepth0, perDepth1);
      }
      if (visible) {
        const uint slot = atomicAdd(s_count, 1u);
        if (slot < uint(MAX_TILE_LIGHTS)) s_lights[slot] = i;
      }
    }
  }
  barrier();

  // Refine the tile's list into its quarters' lists: (light, quarter) pairs
  // spread over the group (a handful per invocation).
  const uint count = s_count;
  if (count <= uint(MAX_TILE_LIGHTS)) {
    for (uint k = local; k < 4u * count; k += uint(TILE_SIZE * TILE_SIZE)) {
      const uint q = k & 3u, light = s_lights[k >> 2u];
      if (s_quarterMax[q] == 0u && s_quarterMin[q] == 0x7f7fffffu) continue;  // no pixel of the quarter is lit
      const vec4 pr = lights[light].positionRadius;
      bool visible = true;
      if (pr.w >= 0.0) {
        // Quarter q: the low or high half in x (bit 0) and in y (bit 1); the
        // high half takes the odd column/row of an odd TILE_SIZE.
        const uvec2 tileMin = gl_WorkGroupID.xy * uvec2(TILE_SIZE), high = uvec2(q & 1u, q >> 1u);
        const uvec2 qMin = tileMin + high * kHalf, qMax = tileMin + mix(uvec2(kHalf), uvec2(TILE_SIZE), bvec2(high));
        vec2 perDepth0, perDepth1;
        frustumPerDepth(qMin, qMax, perDepth0, perDepth1);
        const vec3 c = (u_view * vec4(pr.xyz, 1.0)).xyz;
        visible = sphereMeetsFrustumBox(vec3(c.xy, -c.z), slackRadius(pr.w), uintBitsToFloat(s_quarterMin[q]),
                                        uintBitsToFloat(s_quarterMax[q]), perDepth0, perDepth1);
      }
      if (visible) s_quarterLights[q][atomicAdd(s_quarterCount[q], 1u)] = light;
    }
  }
  barrier();

  if (!inside || !s.covered) return;  // the target's clear value (background) stays
  const vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  vec3 color = vec3(0.0);
  if (u_load != 0) color = imageLoad(u_target, px).rgb;
  if (u_ambientAndSun != 0) color += ambientTerm(s) + shadeDirectionalLight(s, V);
  if (count <= uint(MAX_TILE_LIGHTS)) {
    const uint quarterCount = s_quarterCount[quarter];
    for (uint i = 0u; i < quarterCount; ++i) color += shadePointLight(lights[s_quarterLights[quarter][i]], s, V);
  } else {
    // More lights reach this tile than the list holds: shade them all (correct, slow).
    for (int i = 0; i < u_pointLightCount; ++i) color += shadePointLight(lights[i], s, V);
  }
  imageStore(u_target, px, vec4(color, 1.0));
}
