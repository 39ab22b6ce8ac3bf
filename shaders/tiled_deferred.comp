#version 450 core
// Tiled deferred lighting: one work group per TILE_SIZE x TILE_SIZE tile of
// the G-buffer. (1) Every invocation reads its pixel's surface and the group
// reduces the view-depth bounds of the tile and of each half row of it (of
// each quarter with FAR_FIELD), and marks which of 32 slices of the tile's
// depth range hold pixels; (2) the group culls its bin's lights against the
// tile (the occupied depth slices, then its bounding sphere,
// include/light_bounds.glsl, against the box bounding the tile's frustum over
// the light's depth range, then a spot light's cone against the tile's box)
// into a shared list, keeping each listed light's sphere in view space;
// (3) it marks which of those lights meet each half row's box (with
// FAR_FIELD: refines the list into one list per 8x8 quarter); (4) every
// pixel shades ambient, the directional light and the lights of its half row
// (its quarter), and stores the HDR result.
// Why half rows: in the many-lights scene the field grows with the light
// count, so a tile covers more of the world at 1,024 lights than at 64 and
// its list holds ~3x the lights any one pixel is reached by. The pixels of a
// half row lie at nearly one depth even where the tile's span a deep range (a
// floor seen at a slant), so a half row's box is tight, and its list is
// close to the lights that reach its pixels at every N (13.3 lights a pixel at
// 64 lights, 13.5 at 1,024 against 14.1 and 18.4 for 8x8 quarters). A half row
// is TILE_SIZE / 2 pixels: one SIMD row of a CPU rasteriser's 8 lanes, a
// quarter of a GPU warp; every lane of it pays the loop its list makes, so
// the list is the half row's, not the pixel's (a speed matter only: which
// invocations run together never changes the result). The lists are bits
// over the tile's list: TILE_SIZE * 2 half rows x MAX_TILE_LIGHTS bits of
// shared memory, and the view-space spheres 16 bytes a light. Not with
// FAR_FIELD: it shades each listed light without its cut, so its tail
// reaches every pixel of the quarter, and sums the rest per quarter (its
// quarters' lists are bits over the tile's list too).
// Scheduling (include/invocation.glsl): the tile's list is appended in the
// bin's order (cullTile: one barrier, none in a loop: llvmpipe runs a loop
// that holds a barrier much slower, even one it never takes), the bits and
// depth bounds are atomicOr, atomicMin and atomicMax, the far field integer
// atomicAdd: every pixel sums the same lights in the same order whatever
// order the invocations run in.
// The maths is include/lighting.glsl's, as in deferred_lighting.frag and
// light_volume.frag, so the methods agree.
// Shadows (include/shadows.glsl): each shaded light times its visibility;
// with FAR_FIELD the far field's sums (the tails of the lights a tile does
// not list) are not shadowed.
// Defines: one GBUFFER_*, one LIGHTING_*, one ATTENUATION_*, the shadow ones; TILE_SIZE,
// MAX_TILE_LIGHTS (bounded by GL_MAX_COMPUTE_SHARED_MEMORY_SIZE), TARGET_FORMAT
// (the image format qualifier of the target: rgba16f or rgba32f).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#include "include/shadows.glsl"
#include "include/tile_cull.glsl"
#include "include/light_bounds.glsl"
#ifndef TILE_SIZE
#define TILE_SIZE 16
#endif
#include "include/tile_bins.glsl"
#if defined(FAR_FIELD)
// Cubes 0..3: the quarters' far fields (lights of the tile's list not in
// the quarter's), cube 4: the tile's (lights not in its list).
#define FAR_FIELD_CUBES 5
#include "include/far_field.glsl"
// Invocations that cull and sum the far field: a multiple of 4, so that each
// keeps one quarter in the refine loop (its summing point).
const uint kLanes = uint(TILE_SIZE * TILE_SIZE) & ~3u;
// Unlisted lights closer to the tile's point than FAR_FIELD_NEAR times their
// radius vary across the tile: they are summed at each quarter's point (the
// refine loop) instead of once at the tile's, up to FAR_FIELD_MID of them.
#ifndef FAR_FIELD_NEAR
#define FAR_FIELD_NEAR 2.0
#endif
#define FAR_FIELD_MID 256
// Per quarter and direction bin, what its pixels shade (the tile's set moved
// to the quarter's point plus the quarter's): radiance, weighted direction,
// gradient of the weight, mean light position from the quarter's point.
// s_farBins[quarter]: a bit per bin that holds light, so that pixels visit
// only those (half the bins are empty on a floor under the lights), in order.
shared vec3 s_farShade[4][FAR_FIELD_BINS][4];
shared uint s_farBins[4];
shared uint s_midLights[FAR_FIELD_MID];
shared vec3 s_farPoint[FAR_FIELD_CUBES];  // where each set was summed
#else
const uint kLanes = uint(TILE_SIZE * TILE_SIZE);
#endif

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
#include "include/invocation.glsl"
// The culling's shared words: invocation j < kBlocks tests a run of the
// tile's candidates (the j-th kBlocks-th of them) and counts in s_cullKept[0][j]
// those it lists and in s_cullKept[1][j] (FAR_FIELD) the near unlisted ones;
// s_tileCount: the list's and the near list's lengths. 16 runs: on llvmpipe
// (invocations run a SIMD row after another) the tests cost the same
// however few invocations share them, and a run's place is the sum of the
// counts before it, so fewer runs sum less (64 runs were 5% slower).
const uint kBlocks = min(kLanes, 16u);
#if defined(FAR_FIELD)
const uint kCullSets = 2u;
#else
const uint kCullSets = 1u;
#endif
shared uint s_cullKept[kCullSets][kBlocks];
shared uint s_tileCount[2];
#if RGRAPH_PERMUTE_INVOCATIONS == 5
shared uint s_cullAtomic[2];
#endif

// The counts of set `set` of the runs before run j.
uint cullKeptBefore(uint set, uint j) {
  uint n = 0u;
  for (uint w = 0u; w < j; ++w) n += s_cullKept[set][w];
  return n;
}

#include "include/lights.glsl"
layout(TARGET_FORMAT, binding = 0) uniform image2D u_target;
uniform int u_pointLightCount;
uniform int u_ambientAndSun;  // 1: add ambient and the directional light
uniform int u_load;           // 1: add to what the target holds (e.g. an ambient pass's output)

shared uint s_minDepth;  // floatBitsToUint of the positive view depth (orders like the float)
shared uint s_maxDepth;
shared uint s_depthMask;  // 2.5D culling: bit b set when a pixel's depth falls in slice b of [min, max]
shared uint s_lights[MAX_TILE_LIGHTS];
const uint kHalf = uint(TILE_SIZE) / 2u;
const uint kListWords = (uint(MAX_TILE_LIGHTS) + 31u) / 32u;  // a bit per entry of s_lights
#if defined(FAR_FIELD)
shared uint s_quarterMin[4], s_quarterMax[4];
// Quarter q shades the tile's light e when bit e % 32 of s_quarterLights[q][e / 32]
// is set: in the tile's list order, whichever invocation marked it.
shared uint s_quarterLights[4][kListWords];
#else
// Half row `row` (local y * 2 + (local x >= kHalf)) shades the
// tile's light e when bit e % 32 of s_rowLights[row][e / 32] is set; s_view[e]
// is that light's bounding sphere in view space (x, y, depth, slack radius;
// radius negative: no cut-off), found once in the tile's culling loop.
#define ROW_LISTS 1
const uint kRows = uint(TILE_SIZE) * 2u;
shared vec4 s_view[MAX_TILE_LIGHTS];
shared uint s_rowMin[kRows], s_rowMax[kRows];
shared uint s_rowLights[kRows][kListWords];
#endif

// The slice (0..31) of [minDepth, minDepth + 32 / scale] a view depth falls in.
// Pixels and lights use this one function, so that, floor being monotonic, a
// light spanning depths [a, b] spans the slices of every depth between them.
int depthSlice(float depth, float minDepth, float scale) {
  return clamp(int(floor((depth - minDepth) * scale)), 0, 31);
}

// What the culling loop tests the tile's candidates against, the same in
// every invocation.
struct TileCull {
  uint record, candidates, mask;
  bool binned;
  vec4 viewRowZ;
  float minDepth, maxDepth, sliceScale;
  vec2 perDepth0, perDepth1;
  vec3 boxLo, boxHi, farPoint;
};

uint candidateLight(TileCull t, uint p) { return t.binned ? bins[t.record + uint(BIN_HEADER) + p] : p; }

// A light's bounding sphere in view space: x, y, depth, slack radius (radius
// negative: no cut-off), as cullTest finds it.
vec4 viewSphere(TileCull t, vec4 pr) {
  if (pr.w < 0.0) return vec4(0.0, 0.0, 0.0, -1.0);
  return vec4((u_view * vec4(pr.xyz, 1.0)).xy, -dot(t.viewRowZ, vec4(pr.xyz, 1.0)), slackRadius(pr.w));
}

// Whether light i may reach the tile; `view`: its bounding sphere in view
// space (ROW_LISTS); `near` (FAR_FIELD): unlisted but near the tile's point.
// addFar: add an unlisted light that is not near to the tile's far field.
bool cullTest(TileCull t, uint i, bool addFar, out vec4 view, out bool near) {
  const vec4 pr = lightBounds(lights[i]);
  bool visible = true;
  view = vec4(0.0, 0.0, 0.0, -1.0);
  near = false;
  if (pr.w >= 0.0) {
    const float r = slackRadius(pr.w);
    // The depth test first: it needs only the view matrix's z row.
    const float depth = -dot(t.viewRowZ, vec4(pr.xyz, 1.0));
    const float z0 = max(depth - r, t.minDepth), z1 = min(depth + r, t.maxDepth);
    visible = z0 <= z1;
    if (visible) {
      const int lo = depthSlice(z0, t.minDepth, t.sliceScale), hi = depthSlice(z1, t.minDepth, t.sliceScale);
      visible = (t.mask & ((0xffffffffu >> uint(31 - hi)) & (0xffffffffu << uint(lo)))) != 0u;
    }
    if (visible) {
      view = vec4((u_view * vec4(pr.xyz, 1.0)).xy, depth, r);
      visible = sphereMeetsFrustumBox(view.xyz, r, t.minDepth, t.maxDepth, t.perDepth0, t.perDepth1);
    }
  }
  if (visible) visible = spotMayReachViewBox(lights[i], t.boxLo, t.boxHi);
#if defined(FAR_FIELD)
  if (!visible) {
    const vec3 toLight = pr.xyz - t.farPoint;
    const float nearDistance = FAR_FIELD_NEAR * pr.w;
    near = dot(toLight, toLight) < nearDistance * nearDistance;
    if (!near && addFar) farFieldAdd(4, lights[i], t.farPoint);  // integer sums: any order
  }
#endif
  return visible;
}

// Light i at place `slot` of the tile's list (kept when the list holds it).
void listLight(uint slot, uint i, vec4 view) {
  if (slot < uint(MAX_TILE_LIGHTS)) {
    s_lights[slot] = i;
#if defined(ROW_LISTS)
    s_view[slot] = view;
#endif
  }
}

// Near light i at place `mid` of the near list, or, past it, in the far field.
void listNear(uint mid, uint i, TileCull t) {
#if defined(FAR_FIELD)
  if (mid < uint(FAR_FIELD_MID))
    s_midLights[mid] = i;
  else
    farFieldAdd(4, lights[i], t.farPoint);
#endif
}

// The tile's list and near list (FAR_FIELD) into s_tileCount, in the
// candidates' order whichever invocation tests which, with one barrier:
// invocation j < kBlocks tests run j of the candidates and counts what it
// keeps; after the barrier it appends its kept ones from the counts of the
// runs before. It keeps the answers for its run's first 32 candidates (every
// bin's list: at most MAX_BIN_LIGHTS (512) / kBlocks a run) and tests the rest
// again (the same test of the same light: the same answers).
// s_tileCount is read after the caller's next barrier. Call in dynamically
// uniform control flow.
void cullTile(TileCull t, uint local) {
  const uint run = (t.candidates + kBlocks - 1u) / kBlocks, runFirst = local * run;
  const uint runEnd = local < kBlocks ? min(runFirst + run, t.candidates) : 0u;
  vec4 view;
  bool near;
  if (run > 32u) {
    // Should the second test ever disagree with the first, a place left
    // unwritten names light 0, never one past the buffer.
    for (uint e = local; e < uint(MAX_TILE_LIGHTS); e += kGroupInvocations) s_lights[e] = 0u;
#if defined(FAR_FIELD)
    for (uint e = local; e < uint(FAR_FIELD_MID); e += kGroupInvocations) s_midLights[e] = 0u;
#endif
  }
  uint kept = 0u, nearKept = 0u, mine = 0u, mineNear = 0u;  // bit k: candidate runFirst + k
  for (uint p = runFirst; p < runEnd; ++p) {
    const uint i = candidateLight(t, p), bit = p - runFirst < 32u ? 1u << (p - runFirst) : 0u;
    const bool visible = cullTest(t, i, true, view, near);
#if RGRAPH_PERMUTE_INVOCATIONS == 5
    // Broken on purpose (include/invocation.glsl): the places atomicAdd gives.
    if (visible) listLight(atomicAdd(s_cullAtomic[0], 1u), i, view);
    if (near) listNear(atomicAdd(s_cullAtomic[1], 1u), i, t);
#endif
    if (visible) {
      ++kept;
      mine |= bit;
    }
    if (near) {
      ++nearKept;
      mineNear |= bit;
    }
  }
  if (local < kBlocks) {
    s_cullKept[0][local] = kept;
    if (kCullSets > 1u) s_cullKept[kCullSets - 1u][local] = nearKept;
  }
  groupBarrier();
#if RGRAPH_PERMUTE_INVOCATIONS == 5
  if (local == 0u) {
    s_tileCount[0] = s_cullAtomic[0];
    s_tileCount[1] = s_cullAtomic[1];
  }
#else
  if (local < kBlocks) {
    uint slot = cullKeptBefore(0u, local);
    uint mid = kCullSets > 1u ? cullKeptBefore(kCullSets - 1u, local) : 0u;
    for (uint p = runFirst; p < runEnd; ++p) {
      const uint i = candidateLight(t, p), k = p - runFirst;
      bool visible;
      if (k < 32u) {
        visible = ((mine >> k) & 1u) != 0u;
        near = ((mineNear >> k) & 1u) != 0u;
        // The sphere again: cheaper than keeping 32 across the barrier.
        if (visible) view = viewSphere(t, lightBounds(lights[i]));
      } else {
        visible = cullTest(t, i, false, view, near);
      }
      if (visible) listLight(slot++, i, view);
      if (near) listNear(mid++, i, t);
    }
    if (local == kBlocks - 1u) {
      s_tileCount[0] = slot;
      s_tileCount[1] = mid;
    }
  }
#endif
}

void main() {
  const ivec2 size = ivec2(u_viewport.xy);
  // The pixel, quarter and half row are functions of the (permutable,
  // include/invocation.glsl) IDs; which invocations run together does not
  // matter to the result: a half row is a unit of work (one list), not a
  // set of lanes that run together. It matters to the speed: llvmpipe runs 8
  // neighbouring invocations (x-major, one half row at TILE_SIZE 16) as one
  // SIMD row, which then loops over one list; a 32-wide warp over 4 half
  // rows loops over the union of theirs.
  const uvec2 group = groupId().xy, lid = localId().xy, tileMin = group * uvec2(TILE_SIZE);
  const ivec2 px = ivec2(tileMin + lid);
  const uint local = localIndex();
  const bool inside = px.x < size.x && px.y < size.y;
  const uint quarter = (lid.x >= kHalf ? 1u : 0u) + (lid.y >= kHalf ? 2u : 0u);

  if (local == 0u) {
    s_minDepth = 0x7f7fffffu;
    s_maxDepth = 0u;
    s_depthMask = 0u;
    s_tileCount[0] = 0u;
    s_tileCount[1] = 0u;
#if RGRAPH_PERMUTE_INVOCATIONS == 5
    s_cullAtomic[0] = 0u;
    s_cullAtomic[1] = 0u;
#endif
  }
#if defined(ROW_LISTS)
  const uint row = lid.y * 2u + (lid.x >= kHalf ? 1u : 0u);
  if (local < kRows) {
    s_rowMin[local] = 0x7f7fffffu;
    s_rowMax[local] = 0u;
  }
  for (uint w = local; w < kRows * kListWords; w += uint(TILE_SIZE * TILE_SIZE))
    s_rowLights[w / kListWords][w % kListWords] = 0u;
#endif
#if defined(FAR_FIELD)
  if (local < 4u) {
    s_quarterMin[local] = 0x7f7fffffu;
    s_quarterMax[local] = 0u;
  }
  for (uint w = local; w < 4u * kListWords; w += uint(TILE_SIZE * TILE_SIZE)) s_quarterLights[w / kListWords][w % kListWords] = 0u;
  farFieldClear(local, uint(TILE_SIZE * TILE_SIZE));
  if (local < 4u) s_farBins[local] = 0u;
#endif
  groupBarrier();

  Surface s;
  s.covered = false;
  float viewDepth = 0.0;
  if (inside) {
    s = readSurface(px);
    if (s.covered) {
      viewDepth = max(-(u_view * vec4(s.position, 1.0)).z, 0.0);
      atomicMin(s_minDepth, floatBitsToUint(viewDepth));
      atomicMax(s_maxDepth, floatBitsToUint(viewDepth));
#if defined(ROW_LISTS)
      atomicMin(s_rowMin[row], floatBitsToUint(viewDepth));
      atomicMax(s_rowMax[row], floatBitsToUint(viewDepth));
#else
      atomicMin(s_quarterMin[quarter], floatBitsToUint(viewDepth));
      atomicMax(s_quarterMax[quarter], floatBitsToUint(viewDepth));
#endif
    }
  }
  // Depth bounds and slice bits: atomicMin, atomicMax and atomicOr, the same
  // in any order.
  groupBarrier();

  const bool tileCovered = s_maxDepth != 0u || s_minDepth != 0x7f7fffffu;
  const float minDepth = uintBitsToFloat(s_minDepth);
  const float maxDepth = uintBitsToFloat(s_maxDepth);
  // Slices of the tile's depth range that hold pixels: a tile over a depth
  // discontinuity (a near object in front of a far one) then rejects the
  // lights in the empty gap between them, which the depth bounds keep.
  const float sliceScale = 32.0 / max(maxDepth - minDepth, 1e-6);
  if (inside && s.covered) atomicOr(s_depthMask, 1u << uint(depthSlice(viewDepth, minDepth, sliceScale)));
  groupBarrier();

  if (tileCovered && u_pointLightCount > 0) {  // the same for the whole group
    vec2 perDepth0, perDepth1;
    frustumPerDepth(tileMin, tileMin + uvec2(TILE_SIZE), perDepth0, perDepth1);
    const uint mask = s_depthMask;
    const vec4 viewRowZ = vec4(u_view[0][2], u_view[1][2], u_view[2][2], u_view[3][2]);
#if defined(FAR_FIELD)
    const vec3 farPoint = frustumMidPoint(perDepth0, perDepth1, minDepth, maxDepth);
    if (local == 0u) s_farPoint[4] = farPoint;
#endif
    // The lights of the tile's bin (tiled_bin.comp), or every light when the
    // bin's list overflowed.
    const uvec2 bin = group / uint(BIN_TILES);
    const uint record = binRecord(bin);
    const bool binned = binFits(bin, uint(bins.length())) && bins[record] <= uint(MAX_BIN_LIGHTS);
    const uint candidates = binned ? bins[record] : uint(u_pointLightCount);
    // The view-space box around the tile's frustum between its depths (spot cones).
    const vec3 boxLo = vec3(min(perDepth0 * minDepth, perDepth0 * maxDepth), -maxDepth);
    const vec3 boxHi = vec3(max(perDepth1 * minDepth, perDepth1 * maxDepth), -minDepth);
    // Listed in the bin's order (tiled_bin.comp: the lights' order)
    // whichever invocation tests which (cullTile): the pixels sum their
    // lights in list order, and a list cut at MAX_TILE_LIGHTS or FAR_FIELD_MID
    // keeps its first ones.
    TileCull t;
    t.record = record;
    t.candidates = candidates;
    t.mask = mask;
    t.binned = binned;
    t.viewRowZ = viewRowZ;
    t.minDepth = minDepth;
    t.maxDepth = maxDepth;
    t.sliceScale = sliceScale;
    t.perDepth0 = perDepth0;
    t.perDepth1 = perDepth1;
    t.boxLo = boxLo;
    t.boxHi = boxHi;
#if defined(FAR_FIELD)
    t.farPoint = farPoint;
#else
    t.farPoint = vec3(0.0);
#endif
    cullTile(t, local);
#if defined(FAR_FIELD)
    // The bin's far field (the lights its list leaves out), moved to the
    // tile's point to first order: direction bin `local`.
    if (binned && local < uint(FAR_FIELD_BINS)) {
      vec3 v[4];
      binFarField(record, local, v);
      farFieldMove(v, farPoint - binFarFieldPoint(record));
      farFieldAddSums(4, int(local), v);
    }
#endif
  }
  groupBarrier();
  // The tile's list's length (past MAX_TILE_LIGHTS too: then every pixel
  // shades every light), the same in every invocation.
  const uint count = s_tileCount[0];
#if defined(FAR_FIELD)
  const uint midCount = min(s_tileCount[1], uint(FAR_FIELD_MID));
#endif

  // With FAR_FIELD, refine the tile's list into its quarters' lists:
  // (light, quarter) pairs spread over the group (a handful per invocation);
  // the lights a quarter drops go to its far field.
#if defined(FAR_FIELD)
  if (count <= uint(MAX_TILE_LIGHTS)) {
    // k & 3 == local & 3 (kLanes is a multiple of 4): one quarter per invocation.
    vec3 farPoint = vec3(0.0);
    {
      const uvec2 high = uvec2(local & 1u, (local >> 1u) & 1u);
      vec2 perDepth0, perDepth1;
      frustumPerDepth(tileMin + high * kHalf, tileMin + mix(uvec2(kHalf), uvec2(TILE_SIZE), bvec2(high)), perDepth0,
                      perDepth1);
      farPoint = frustumMidPoint(perDepth0, perDepth1, uintBitsToFloat(s_quarterMin[local & 3u]),
                               uintBitsToFloat(s_quarterMax[local & 3u]));
      if (local < 4u) s_farPoint[local] = farPoint;
    }
    for (uint k = local; k < 4u * (count + midCount) && local < kLanes; k += kLanes) {
      const uint q = k & 3u;
      if (s_quarterMax[q] == 0u && s_quarterMin[q] == 0x7f7fffffu) continue;  // no pixel of the quarter is lit
      if ((k >> 2u) >= count) {  // a near unlisted light: at the quarter's point
        farFieldAdd(int(q), lights[s_midLights[(k >> 2u) - count]], farPoint);
        continue;
      }
      const uint light = s_lights[k >> 2u];
      const vec4 pr = lightBounds(lights[light]);
      bool visible = true;
      if (pr.w >= 0.0) {
        // Quarter q: the low or high half in x (bit 0) and in y (bit 1); the
        // high half takes the odd column/row of an odd TILE_SIZE.
        const uvec2 high = uvec2(q & 1u, q >> 1u);
        const uvec2 qMin = tileMin + high * kHalf, qMax = tileMin + mix(uvec2(kHalf), uvec2(TILE_SIZE), bvec2(high));
        vec2 perDepth0, perDepth1;
        frustumPerDepth(qMin, qMax, perDepth0, perDepth1);
        const vec3 c = (u_view * vec4(pr.xyz, 1.0)).xyz;
        visible = sphereMeetsFrustumBox(vec3(c.xy, -c.z), slackRadius(pr.w), uintBitsToFloat(s_quarterMin[q]),
                                        uintBitsToFloat(s_quarterMax[q]), perDepth0, perDepth1);
      }
      const uint e = k >> 2u;
      if (visible)
        atomicOr(s_quarterLights[q][e / 32u], 1u << (e % 32u));
      else
        farFieldAdd(int(q), lights[light], farPoint);
    }
  }
#else
  // Mark, per half row, the tile's lights that meet its box: the row's own
  // invocations split the tile's list (lane j takes every lanes-th light from
  // j), so that the row's frustum is found once and each 32 lights cost a
  // lane one shared-memory atomic.
  if (count <= uint(MAX_TILE_LIGHTS) && !(s_rowMax[row] == 0u && s_rowMin[row] == 0x7f7fffffu)) {
    const uint high = row & 1u, lanes = high != 0u ? uint(TILE_SIZE) - kHalf : kHalf;
    const uint lane = lid.x - high * kHalf;
    const uvec2 rowMin = tileMin + uvec2(high * kHalf, lid.y);
    vec2 perDepth0, perDepth1;
    frustumPerDepth(rowMin, uvec2(tileMin.x + kHalf + high * (uint(TILE_SIZE) - kHalf), rowMin.y + 1u), perDepth0,
                    perDepth1);
    const float rowNear = uintBitsToFloat(s_rowMin[row]), rowFar = uintBitsToFloat(s_rowMax[row]);
    for (uint w = 0u; w * 32u < count; ++w) {
      uint bits = 0u;
      for (uint e = w * 32u + lane; e < min(count, w * 32u + 32u); e += lanes) {
        const vec4 v = s_view[e];
        if (v.w < 0.0 || sphereMeetsFrustumBox(v.xyz, v.w, rowNear, rowFar, perDepth0, perDepth1))
          bits |= 1u << (e % 32u);
      }
      if (bits != 0u) atomicOr(s_rowLights[row][w], bits);
    }
  }
#endif
  groupBarrier();
#if defined(FAR_FIELD)
  // Merge the tile's set into each quarter's at the quarter's point, once per
  // (quarter, bin) instead of per pixel.
  if (count <= uint(MAX_TILE_LIGHTS) && tileCovered && u_pointLightCount > 0 && local < 4u * uint(FAR_FIELD_BINS)) {
    const int q = int(local) / FAR_FIELD_BINS, b = int(local) % FAR_FIELD_BINS;
    vec3 t[4], v[4];
    farFieldLoad(4, b, t);
    farFieldLoad(q, b, v);
    const vec3 offset = s_farPoint[q] - s_farPoint[4];
    const float scale = farFieldScaleAt(t[0], t[2], offset);
    const float wt = dot(t[0], vec3(1.0 / 3.0)) * scale, wq = dot(v[0], vec3(1.0 / 3.0));
    const vec3 mean = (farFieldMeanLight(t[1], t[3]) - offset) * wt + farFieldMeanLight(v[1], v[3]) * wq;
    if (wt + wq > 0.0) {
      atomicOr(s_farBins[q], 1u << uint(b));
      s_farShade[q][b][0] = t[0] * scale + v[0];
      s_farShade[q][b][1] = t[1] * scale + v[1];
      s_farShade[q][b][2] = t[2] + v[2];
      s_farShade[q][b][3] = mean / (wt + wq);
    }
  }
  groupBarrier();
#endif

  if (!inside || !s.covered) return;  // the target's clear value (background) stays
  const vec3 V = safeNormal(u_cameraPos.xyz - s.position, s.normal);
  vec3 color = vec3(0.0);
  if (u_load != 0) color = imageLoad(u_target, px).rgb;
  if (u_ambientAndSun != 0) color += ambientTerm(s, V) + shadeDirectionalLight(s, V) * sunVisibility(s);
  if (count <= uint(MAX_TILE_LIGHTS)) {
#if defined(FAR_FIELD)
    // The listed lights without their cut (their tails), the rest as the far field.
    for (uint w = 0u; w * 32u < count; ++w)
      for (uint bits = s_quarterLights[quarter][w]; bits != 0u; bits &= bits - 1u) {
        const uint i = s_lights[w * 32u + uint(findLSB(bits))];
        color += shadePointLight(farFieldUncut(lights[i]), s, V) * lightVisibility(int(i), s);
      }
    const vec3 offset = s.position - s_farPoint[quarter];
    for (uint bits = s_farBins[quarter]; bits != 0u; bits &= bits - 1u) {
      const int b = findLSB(bits);
      const vec3 radiance = s_farShade[quarter][b][0];
      color += farFieldShadeBin(radiance, farFieldScaleAt(radiance, s_farShade[quarter][b][2], offset),
                                s_farShade[quarter][b][1], s_farShade[quarter][b][3] - offset, s, V);
    }
#else
    // The row's lights: the set bits of its words over the quarter's list.
    for (uint w = 0u; w * 32u < count; ++w)
      for (uint bits = s_rowLights[row][w]; bits != 0u; bits &= bits - 1u) {
        const uint i = s_lights[w * 32u + uint(findLSB(bits))];
        color += shadePointLight(lights[i], s, V) * lightVisibility(int(i), s);
      }
#endif
  } else {
    // More lights reach this tile than the list holds: shade them all (correct, slow;
    // FAR_FIELD: without their cut, so exact).
#if defined(FAR_FIELD)
    for (int i = 0; i < u_pointLightCount; ++i)
      color += shadePointLight(farFieldUncut(lights[i]), s, V) * lightVisibility(i, s);
#else
    for (int i = 0; i < u_pointLightCount; ++i) color += shadePointLight(lights[i], s, V) * lightVisibility(i, s);
#endif
  }
  if (u_ambientAndSun != 0) color += emissiveTerm(s);  // once per pixel: with the ambient
  imageStore(u_target, px, vec4(color, 1.0));
}
