#version 450 core
// clustered_deferred's far field (FAR_FIELD), after the lists
// (clustered_build.comp) and the bins (tiled_bin.comp, bins aligned to the
// cluster tiles): one work group per cluster tile finds which of its
// clusters hold pixels and their pixels' depth range, and for each sums the
// far field of the lights its list leaves out (far_field.glsl) at the
// cluster's point (the tile's middle ray, halfway through those depths):
// the bin's far field (the lights beyond twice their radius from the bin's
// pixels) moved there to first order, plus the bin's listed lights that the
// cluster does not list, summed there. It stores what the cluster's pixels
// shade (include/cluster_far_field.glsl); a cluster without pixels or whose
// list overflowed (its pixels shade every light) gets nothing, and so do the
// tile's clusters with pixels past the first FAR_CLUSTERS (only with more
// slices than that: they keep their listed lights, without the far field).
// All of a tile's clusters are summed at once, spread over the group (one
// cluster after the other, each with its barriers, cost llvmpipe ~1 s a
// frame at 640x360): which bin-listed lights each cluster lists is marked
// through a hash of the bin's list (light -> position) in shared memory.
// A light the cluster lists but its bin does not (the cluster's box spans
// its whole depth slice, the bin only its pixels' depths) is in both: it is
// counted twice, at a level far below the cut-off (it is more than twice its
// radius from every pixel of the bin).
// Defines: GBUFFER_*, LIGHTING_*, ATTENUATION_*, the grid (TILE_SIZE, SLICES,
// MAX_CLUSTER_LIGHTS: the pass's own lists), the bins' (light_bins.cpp).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
#include "include/lighting.glsl"
#define CLUSTER_GRID_DEFINES
#include "include/clusters.glsl"
#include "include/tile_cull.glsl"
#include "include/tile_bins.glsl"
// Clusters of a tile summed at once: their sums take 768 bytes each of the
// 32 KiB of shared memory every GL 4.5 device has (with the bin's hash and
// marks, 8 KiB, and the slices' depths, 8 bytes a slice).
#define FAR_CLUSTERS 24
#define FAR_FIELD_CUBES FAR_CLUSTERS
#include "include/far_field.glsl"
#define CLUSTER_FAR_FIELD_WRITER
#include "include/cluster_far_field.glsl"

layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;
#include "include/invocation.glsl"
#include "include/ordered_append.glsl"

#include "include/lights.glsl"
uniform int u_pointLightCount;

const uint kGroup = 256u;
#define HASH_SIZE 1024u  // > 2 x MAX_BIN_LIGHTS: short probes
shared uint s_sliceMin[SLICES], s_sliceMax[SLICES];  // floatBitsToUint of the pixels' view depths
shared int s_slice[FAR_CLUSTERS];        // the slice of summed cluster o
shared vec3 s_point[FAR_CLUSTERS];       // where it is summed
shared uint s_bins[FAR_CLUSTERS];        // its direction bins that hold light
shared uint s_hash[HASH_SIZE];           // (light + 1) << 9 | its position in the bin's list; 0: empty
shared uint s_listedBy[MAX_BIN_LIGHTS];  // bit o: summed cluster o lists the bin's light at this position

uint hashOf(uint light) { return (light * 2654435761u) >> 22u; }  // 10 bits: HASH_SIZE

// Where a light lands depends on the order of the inserts (linear probing),
// what hashFind returns does not: each light is in the bin's list once.
void hashInsert(uint light, uint position) {
  const uint entry = ((light + 1u) << 9u) | position;
  for (uint h = hashOf(light), n = 0u; n < HASH_SIZE; ++n, h = (h + 1u) & (HASH_SIZE - 1u))
    if (atomicCompSwap(s_hash[h], 0u, entry) == 0u) return;
}

// The position of `light` in the bin's list, or MAX_BIN_LIGHTS when it is not there.
uint hashFind(uint light) {
  for (uint h = hashOf(light), n = 0u; n < HASH_SIZE; ++n, h = (h + 1u) & (HASH_SIZE - 1u)) {
    const uint e = s_hash[h];
    if (e == 0u) break;
    if ((e >> 9u) == light + 1u) return e & 511u;
  }
  return uint(MAX_BIN_LIGHTS);
}

uint clusterBase(int cluster) { return uint(clusterCount()) + uint(cluster) * uint(MAX_CLUSTER_LIGHTS); }

void main() {
  const uint local = localIndex();
  const ivec2 tile = ivec2(groupId().xy);
  const ivec2 size = ivec2(u_viewport.xy);
  // The same for the whole group: lists and records for this viewport.
  if (!clusterListsFit(uint(data.length())) || !clusterFarFieldsFit(uint(farFields.length())) ||
      any(greaterThanEqual(tile, clusterTiles())))
    return;
  for (uint i = local; i < uint(SLICES); i += kGroup) {
    s_sliceMin[i] = 0x7f7fffffu;
    s_sliceMax[i] = 0u;
  }
  for (uint i = local; i < HASH_SIZE; i += kGroup) s_hash[i] = 0u;
  for (uint i = local; i < uint(MAX_BIN_LIGHTS); i += kGroup) s_listedBy[i] = 0u;
  if (local < uint(FAR_CLUSTERS)) s_bins[local] = 0u;
  orderedAppendInit(local);
  farFieldClear(local, kGroup);
  // The tile's bin's list (hashed below), or every light when it overflowed.
  const uvec2 bin = uvec2(tile) / uint(BIN_TILES);
  const uint binAt = binRecord(bin);
  const bool binned = binFits(bin, uint(bins.length())) && bins[binAt] <= uint(MAX_BIN_LIGHTS) &&
                      u_pointLightCount < (1 << 22);
  const uint candidates = binned ? bins[binAt] : uint(u_pointLightCount);
  groupBarrier();

  // The slices' depth bounds (atomicMin, atomicMax) and the hash: the same
  // in any order.
  const ivec2 at = ivec2(localId().xy);
  for (int y = at.y; y < TILE_SIZE; y += 16)
    for (int x = at.x; x < TILE_SIZE; x += 16) {
      const ivec2 px = tile * TILE_SIZE + ivec2(x, y);
      if (px.x >= size.x || px.y >= size.y) continue;
      const Surface s = readSurface(px);
      if (!s.covered) continue;
      const float depth = max(-(u_view * vec4(s.position, 1.0)).z, 0.0);
      const int slice = clusterSlice(depth);
      atomicMin(s_sliceMin[slice], floatBitsToUint(depth));
      atomicMax(s_sliceMax[slice], floatBitsToUint(depth));
    }
  if (binned)
    for (uint j = local; j < candidates; j += kGroup) hashInsert(bins[binAt + uint(BIN_HEADER) + j], j);
  groupBarrier();

  // The clusters to sum: with pixels, lights, and a list that did not overflow.
  vec2 perDepth0, perDepth1;
  frustumPerDepth(uvec2(tile * TILE_SIZE), uvec2((tile + 1) * TILE_SIZE), perDepth0, perDepth1);
  // Summed cluster o: the o-th such slice from the camera (whichever
  // invocation tests which: include/ordered_append.glsl), so that with more
  // than FAR_CLUSTERS the nearest are summed.
  uint summed = 0u;
  for (int first = 0; first < SLICES; first += int(kGroup)) {
    const int slice = first + int(local);
    const int cluster = clusterIndex(tile, min(slice, SLICES - 1));
    const bool sums = slice < SLICES && s_sliceMin[slice] != 0x7f7fffffu &&
                      data[cluster] <= uint(MAX_CLUSTER_LIGHTS) && u_pointLightCount > 0;
    uint kept = 0u;
    const uint o = summed + orderedAppend(sums, local, kept);
    summed += kept;
    if (sums && o < uint(FAR_CLUSTERS)) {
      s_slice[o] = slice;
      s_point[o] = frustumMidPoint(perDepth0, perDepth1, uintBitsToFloat(s_sliceMin[slice]),
                                   uintBitsToFloat(s_sliceMax[slice]));
    } else if (slice < SLICES) {
      farFields[uint(cluster) * uint(CLUSTER_FAR_RECORD)] = 0u;  // nothing to add
    }
  }
  groupBarrier();
  summed = min(summed, uint(FAR_CLUSTERS));

  // Which of the bin's lights each cluster lists.
  if (binned)
    for (uint o = 0u; o < summed; ++o) {
      const int cluster = clusterIndex(tile, s_slice[o]);
      const uint base = clusterBase(cluster), count = data[cluster];
      for (uint k = local; k < count; k += kGroup) {
        const uint at = hashFind(data[base + k]);
        if (at < uint(MAX_BIN_LIGHTS)) atomicOr(s_listedBy[at], 1u << o);
      }
    }
  groupBarrier();

  // The bin's far field moved to each cluster's point, and the bin's lights
  // the cluster does not list summed there: (cluster, light) pairs over the
  // group, into integer sums (far_field.glsl): the same in any order.
  if (binned)
    for (uint k = local; k < summed * uint(FAR_FIELD_BINS); k += kGroup) {
      const uint o = k / uint(FAR_FIELD_BINS), b = k % uint(FAR_FIELD_BINS);
      vec3 v[4];
      binFarField(binAt, b, v);
      farFieldMove(v, s_point[o] - binFarFieldPoint(binAt));
      farFieldAddSums(int(o), int(b), v);
    }
  for (uint k = local; k < summed * candidates; k += kGroup) {
    const uint o = k % summed, j = k / summed;
    bool listed = false;
    uint light = j;
    if (binned) {
      light = bins[binAt + uint(BIN_HEADER) + j];
      listed = (s_listedBy[j] & (1u << o)) != 0u;
    } else {  // every light: look it up in the cluster's list
      const int cluster = clusterIndex(tile, s_slice[o]);
      const uint base = clusterBase(cluster), count = data[cluster];
      for (uint e = 0u; e < count && !listed; ++e) listed = data[base + e] == light;
    }
    if (!listed) farFieldAdd(int(o), lights[light], s_point[o]);
  }
  groupBarrier();

  // What each cluster's pixels shade per direction bin.
  for (uint k = local; k < summed * uint(FAR_FIELD_BINS); k += kGroup) {
    const uint o = k / uint(FAR_FIELD_BINS), b = k % uint(FAR_FIELD_BINS);
    const uint record = uint(clusterIndex(tile, s_slice[o])) * uint(CLUSTER_FAR_RECORD);
    vec3 v[4];
    farFieldLoad(int(o), int(b), v);
    if (dot(v[0], vec3(1.0 / 3.0)) > 0.0) atomicOr(s_bins[o], 1u << b);
    v[3] = farFieldMeanLight(v[1], v[3]);
    for (uint j = 0u; j < 4u; ++j)
      for (uint c = 0u; c < 3u; ++c) farFields[record + 4u + b * 12u + j * 3u + c] = floatBitsToUint(v[j][c]);
  }
  groupBarrier();
  if (local < summed) {
    const uint record = uint(clusterIndex(tile, s_slice[local])) * uint(CLUSTER_FAR_RECORD);
    farFields[record] = s_bins[local];
    farFields[record + 1u] = floatBitsToUint(s_point[local].x);
    farFields[record + 2u] = floatBitsToUint(s_point[local].y);
    farFields[record + 3u] = floatBitsToUint(s_point[local].z);
  }
}
