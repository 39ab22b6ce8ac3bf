#version 450 core
// tiled_deferred, step 1: one work group per bin of BIN_TILES x BIN_TILES
// tiles (include/tile_bins.glsl) reduces the view-depth range of its pixels
// and lists the lights whose bounding sphere (include/light_bounds.glsl), its
// radius times BIN_REACH, meets
// the bin's frustum box over that range; tiled_deferred.comp's tiles then
// cull only their bin's list. With FAR_FIELD the lights it does not list
// are summed as the bin's far field (include/far_field.glsl) at the bin's
// middle point; BIN_REACH > 1 keeps the lights near the bin in the list, so
// that the tiles sum those at their own points.
// Defines: as tiled_deferred.comp (GBUFFER_*, LIGHTING_*, ATTENUATION_*,
// TILE_SIZE, FAR_FIELD) and BIN_TILES, MAX_BIN_LIGHTS, BIN_REACH, BIN_BINDING
// (passes/common/light_bins.cpp). clustered_deferred's far field runs it
// too, with its clusters' TILE_SIZE.
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#include "include/tile_cull.glsl"
#include "include/light_bounds.glsl"
#ifndef TILE_SIZE
#define TILE_SIZE 16
#endif
#define BIN_WRITER
#include "include/tile_bins.glsl"
#if defined(FAR_FIELD)
#define FAR_FIELD_CUBES 1
#include "include/far_field.glsl"
#endif

layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;
#include "include/invocation.glsl"
#include "include/ordered_append.glsl"

#include "include/lights.glsl"
uniform int u_pointLightCount;

shared uint s_minDepth, s_maxDepth;

void main() {
  const uint local = localIndex();
  const uvec2 group = groupId().xy, binMin = group * uint(BIN_PIXELS);
  const ivec2 size = ivec2(u_viewport.xy);
  if (local == 0u) {
    s_minDepth = 0x7f7fffffu;
    s_maxDepth = 0u;
  }
  orderedAppendInit(local);
#if defined(FAR_FIELD)
  farFieldClear(local, 256u);
#endif
  groupBarrier();
  // Depth bounds: each invocation reads every 16th pixel in x and y (min and
  // max: the same in any order).
  float lo = 3.0e38, hi = 0.0;
  const uvec2 at = localId().xy;
  for (uint y = at.y; y < uint(BIN_PIXELS); y += 16u)
    for (uint x = at.x; x < uint(BIN_PIXELS); x += 16u) {
      const ivec2 px = ivec2(binMin + uvec2(x, y));
      if (px.x >= size.x || px.y >= size.y) continue;
      const Surface s = readSurface(px);
      if (!s.covered) continue;
      const float depth = max(-(u_view * vec4(s.position, 1.0)).z, 0.0);
      lo = min(lo, depth);
      hi = max(hi, depth);
    }
  if (hi >= lo) {
    atomicMin(s_minDepth, floatBitsToUint(lo));
    atomicMax(s_maxDepth, floatBitsToUint(hi));
  }
  groupBarrier();
  const bool covered = s_maxDepth != 0u || s_minDepth != 0x7f7fffffu;
  const float minDepth = uintBitsToFloat(s_minDepth), maxDepth = uintBitsToFloat(s_maxDepth);
  const uint record = binRecord(group);
  const bool fits = binFits(group, uint(bins.length()));  // the same for the whole group
  vec2 perDepth0, perDepth1;
  frustumPerDepth(binMin, binMin + uvec2(BIN_PIXELS), perDepth0, perDepth1);
  const vec3 point = covered ? frustumMidPoint(perDepth0, perDepth1, minDepth, maxDepth) : vec3(0.0);
  // The list in light order (include/ordered_append.glsl), 256 lights a
  // round: the tiles' lists follow it. The far field of the rest: integer
  // sums (far_field.glsl), the same in any order.
  uint count = 0u;
  for (uint first = 0u; covered && fits && first < uint(u_pointLightCount); first += 256u) {
    const uint i = first + local;
    bool listed = false;
    if (i < uint(u_pointLightCount)) {
      const vec4 pr = lightBounds(lights[i]);
      const vec3 c = (u_view * vec4(pr.xyz, 1.0)).xyz;
      listed = pr.w < 0.0 || sphereMeetsFrustumBox(vec3(c.xy, -c.z), slackRadius(pr.w) * BIN_REACH, minDepth,
                                                   maxDepth, perDepth0, perDepth1);
#if defined(FAR_FIELD)
      if (!listed) farFieldAdd(0, lights[i], point);
#endif
    }
    uint kept = 0u;
    const uint slot = count + orderedAppend(listed, local, kept);
    if (listed && slot < uint(MAX_BIN_LIGHTS)) bins[record + uint(BIN_HEADER) + slot] = i;
    count += kept;
  }
  groupBarrier();
  if (fits && local == 0u) {
    bins[record] = count;
    bins[record + 4u] = floatBitsToUint(point.x);
    bins[record + 5u] = floatBitsToUint(point.y);
    bins[record + 6u] = floatBitsToUint(point.z);
  }
#if defined(FAR_FIELD)
  if (fits && local < uint(FAR_FIELD_VALUES)) bins[record + 8u + local] = floatBitsToUint(farFieldFloat(s_farSums[0][local]));
#endif
}
