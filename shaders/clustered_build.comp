#version 450 core
// Clustered shading, step 1: one work group per screen tile builds the
// light lists of the tile's clusters (include/clusters.glsl) in two steps,
// so that the cost goes as tiles x lights + clusters x the tile's lights
// rather than clusters x lights: (1) the group culls every point light
// against the tile's four side planes into a shared candidate list (view-space
// centres); (2) one invocation per depth slice tests the candidates against
// its cluster's box. The cluster's view-space AABB bounds the frustum
// cell between its tile's four corner rays and its slice's depth range; every
// light whose bounding sphere (include/light_bounds.glsl: the cut-off sphere,
// or the sphere around a spot light's cone; negative radius: no cut-off,
// reaches everything) touches the AABB, and whose cone (spot lights) meets
// the AABB's bounding sphere, is listed. A cluster with more
// than MAX_CLUSTER_LIGHTS lights keeps counting (the lighting pass then shades
// every light there) and adds one to the header's overflow counter.
// CLUSTER_DEPTH_BOUNDS (clustered_deferred's own lists; with the G-buffer's
// and the light bins' defines): the tile culls its light bin's list
// (tiled_bin.comp) instead of every light, and each cluster's box spans its
// pixels' depths instead of its whole slice; a cluster without pixels lists
// nothing. In the many-lights scene at 1,024 lights that halves the lights
// listed per pixel (32-pixel tiles: 49 to 40; 16-pixel: 26).
#include "include/frame.glsl"
#define CLUSTER_LISTS_BUILD
#include "include/clusters.glsl"
#include "include/light_bounds.glsl"
#if defined(CLUSTER_DEPTH_BOUNDS)
// clustered_deferred's own lists: the G-buffer bounds each cluster's depth
// to that of its pixels (a cluster without pixels lists nothing).
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"
// The light bins (tiled_bin.comp, aligned to the tiles; BIN_* defines): a
// tile culls its bin's list instead of every light, so that the culling
// stays flat in the light count at constant overlap.
#include "include/tile_bins.glsl"
shared uint s_sliceMin[SLICES], s_sliceMax[SLICES];  // floatBitsToUint of the pixels' view depths

// Adds a pixel at view depth d to the bounds of its slice, and of the
// neighbouring one when d is within 0.1% of their boundary, so that the
// lighting pass's slice of the pixel (the same function of the same depth)
// has it in its bounds whatever its rounding.
void addPixelDepth(float d) {
  const int lo = clusterSlice(d * 0.999), hi = clusterSlice(d * 1.001);
  for (int slice = lo; slice <= hi; ++slice) {
    atomicMin(s_sliceMin[slice], floatBitsToUint(d));
    atomicMax(s_sliceMax[slice], floatBitsToUint(d));
  }
}
#endif

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
#include "include/invocation.glsl"
#include "include/ordered_append.glsl"

// Candidates one tile holds in shared memory (20 KiB, within the 32 KiB every
// GL 4.5 device has); a tile with more tests every light in step 2.
#define MAX_TILE_CANDIDATES 1024

#include "include/lights.glsl"
uniform int u_pointLightCount;

// View-space point on the ray through NDC `ndc` at positive depth `d`
// (clip.x = P00 x + P20 z with z = -d; P20, P21 carry the jitter).
vec3 rayPoint(vec2 ndc, float d) {
  return vec3((ndc.x + u_proj[2][0]) * d / u_proj[0][0], (ndc.y + u_proj[2][1]) * d / u_proj[1][1], -d);
}

shared uint s_index[MAX_TILE_CANDIDATES];
shared vec4 s_light[MAX_TILE_CANDIDATES];  // xyz view-space centre, w: radius with slack (negative: no cut-off)

// A light's view-space centre and radius with the same slack as
// tiled_deferred (rounding never drops a light a pixel can see).
vec4 viewLight(int i) {
  const vec4 pr = lightBounds(lights[i]);
  return vec4((u_view * vec4(pr.xyz, 1.0)).xyz, pr.w >= 0.0 ? pr.w * 1.001 + 1e-4 : -1.0);
}

// The plane through the eye and the rays through NDC a and b, facing `inside`.
vec3 sidePlane(vec2 a, vec2 b, vec3 inside) {
  const vec3 n = normalize(cross(rayPoint(a, 1.0), rayPoint(b, 1.0)));
  return dot(n, inside) < 0.0 ? -n : n;
}

void main() {
  const ivec2 tiles = clusterTiles();
  const ivec2 tile = ivec2(groupId().xy);
  const uint local = localIndex();
  // The same for the whole group (no return before a barrier).
  const bool builds = clusterListsFit(uint(data.length())) && tile.x < tiles.x && tile.y < tiles.y;
  orderedAppendInit(local);
#if defined(CLUSTER_DEPTH_BOUNDS)
  for (int i = int(local); i < SLICES; i += 64) {
    s_sliceMin[i] = 0x7f7fffffu;
    s_sliceMax[i] = 0u;
  }
  groupBarrier();
  // The slices' depth bounds: atomicMin and atomicMax, the same in any order.
  for (int i = int(local); builds && i < TILE_SIZE * TILE_SIZE; i += 64) {
    const ivec2 px = tile * TILE_SIZE + ivec2(i % TILE_SIZE, i / TILE_SIZE);
    if (px.x >= int(u_viewport.x) || px.y >= int(u_viewport.y)) continue;
    const Surface s = readSurface(px);
    if (s.covered) addPixelDepth(max(-(u_view * vec4(s.position, 1.0)).z, 0.0));
  }
#endif
  groupBarrier();

  const vec2 size = u_viewport.xy;
  const vec2 ndc0 = vec2(tile * TILE_SIZE) / size * 2.0 - 1.0;
  const vec2 ndc1 = min(vec2((tile + 1) * TILE_SIZE), size) / size * 2.0 - 1.0;
  const vec3 centre = rayPoint(0.5 * (ndc0 + ndc1), 1.0);
  const vec3 planes[4] = vec3[4](sidePlane(ndc0, vec2(ndc0.x, ndc1.y), centre), sidePlane(ndc1, vec2(ndc1.x, ndc0.y), centre),
                                 sidePlane(ndc0, vec2(ndc1.x, ndc0.y), centre), sidePlane(ndc1, vec2(ndc0.x, ndc1.y), centre));
#if defined(CLUSTER_DEPTH_BOUNDS)
  const uvec2 bin = uvec2(tile) / uint(BIN_TILES);
  const uint binAt = binRecord(bin);
  const bool binned = binFits(bin, uint(bins.length())) && bins[binAt] <= uint(MAX_BIN_LIGHTS);
  const int culled = binned ? int(bins[binAt]) : u_pointLightCount;
#else
  const bool binned = false;
  const uint binAt = 0u;
  const int culled = u_pointLightCount;
#endif
  // The candidates in the order of what is culled (the bin's list, in light
  // order, or every light), 64 a round, whichever invocation tests which
  // (include/ordered_append.glsl): each cluster's list follows this order,
  // and its pixels sum their lights in it.
  uint count = 0u;
  for (int first = 0; builds && first < culled; first += 64) {
    const int j = first + int(local);
    int i = j;
    vec4 l = vec4(0.0);
    bool visible = false;
    if (j < culled) {
#if defined(CLUSTER_DEPTH_BOUNDS)
      if (binned) i = int(bins[binAt + uint(BIN_HEADER) + uint(j)]);
#endif
      l = viewLight(i);
      visible = true;
      for (int p = 0; p < 4 && visible && l.w >= 0.0; ++p) visible = dot(planes[p], l.xyz) >= -l.w;
    }
    uint kept = 0u;
    const uint slot = count + orderedAppend(visible, local, kept);
    count += kept;
    if (visible && slot < uint(MAX_TILE_CANDIDATES)) {
      s_index[slot] = uint(i);
      s_light[slot] = l;
    }
  }
  groupBarrier();
  const bool candidates = count <= uint(MAX_TILE_CANDIDATES);
  const int tested = candidates ? int(count) : u_pointLightCount;

  for (int slice = int(local); builds && slice < SLICES; slice += 64) {
    // The cluster's box: the tile's corner rays between the slice's depths,
    // with a little depth slack so that a pixel whose slice rounds to this
    // cluster is inside it.
#if defined(CLUSTER_DEPTH_BOUNDS)
    if (s_sliceMin[slice] == 0x7f7fffffu) {  // no pixel
      data[clusterIndex(tile, slice)] = 0u;
      continue;
    }
    const vec2 depth = uintBitsToFloat(uvec2(s_sliceMin[slice], s_sliceMax[slice])) * vec2(0.999, 1.001);
#else
    const vec2 depth = clusterDepthRange(slice) * vec2(0.999, 1.001);
#endif
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int i = 0; i < 8; ++i) {
      const vec3 p = rayPoint(vec2((i & 1) != 0 ? ndc1.x : ndc0.x, (i & 2) != 0 ? ndc1.y : ndc0.y),
                              (i & 4) != 0 ? depth.y : depth.x);
      lo = min(lo, p);
      hi = max(hi, p);
    }
    const int cluster = clusterIndex(tile, slice);
    const uint base = uint(clusterCount()) + uint(cluster) * uint(MAX_CLUSTER_LIGHTS);
    uint listed = 0u;
    for (int j = 0; j < tested; ++j) {
      const vec4 l = candidates ? s_light[j] : viewLight(j);
      const vec3 d = l.xyz - clamp(l.xyz, lo, hi);
      const uint index = candidates ? s_index[j] : uint(j);
      if ((l.w < 0.0 || dot(d, d) <= l.w * l.w) && spotMayReachViewBox(lights[index], lo, hi)) {
        if (listed < uint(MAX_CLUSTER_LIGHTS)) data[base + listed] = index;
        ++listed;
      }
    }
    data[cluster] = listed;
    // A count: the same in any order.
    if (listed > uint(MAX_CLUSTER_LIGHTS)) atomicAdd(overflowedClusters, 1u);
  }
}
