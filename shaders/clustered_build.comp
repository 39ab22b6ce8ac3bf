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
#include "include/frame.glsl"
#include "include/clusters.glsl"
#include "include/light_bounds.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

// Candidates one tile holds in shared memory (20 KiB, within the 32 KiB every
// GL 4.5 device has); a tile with more tests every light in step 2.
#define MAX_TILE_CANDIDATES 1024

layout(std430, binding = 0) readonly buffer Lights { PointLight lights[]; };
layout(std430, binding = 1) buffer Clusters {
  uint overflowedClusters;
  uint header[3];
  uint data[];  // counts[clusterCount()], then indices[clusterCount() * MAX_CLUSTER_LIGHTS]
};
uniform int u_pointLightCount;

// View-space point on the ray through NDC `ndc` at positive depth `d`
// (clip.x = P00 x + P20 z with z = -d; P20, P21 carry the jitter).
vec3 rayPoint(vec2 ndc, float d) {
  return vec3((ndc.x + u_proj[2][0]) * d / u_proj[0][0], (ndc.y + u_proj[2][1]) * d / u_proj[1][1], -d);
}

shared uint s_count;
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
  const ivec2 tile = ivec2(gl_WorkGroupID.xy);
  const uint local = gl_LocalInvocationIndex;
  // The same for the whole group (no return before a barrier).
  const bool builds = clusterListsFit(uint(data.length())) && tile.x < tiles.x && tile.y < tiles.y;
  if (local == 0u) s_count = 0u;
  barrier();

  const vec2 size = u_viewport.xy;
  const vec2 ndc0 = vec2(tile * TILE_SIZE) / size * 2.0 - 1.0;
  const vec2 ndc1 = min(vec2((tile + 1) * TILE_SIZE), size) / size * 2.0 - 1.0;
  const vec3 centre = rayPoint(0.5 * (ndc0 + ndc1), 1.0);
  const vec3 planes[4] = vec3[4](sidePlane(ndc0, vec2(ndc0.x, ndc1.y), centre), sidePlane(ndc1, vec2(ndc1.x, ndc0.y), centre),
                                 sidePlane(ndc0, vec2(ndc1.x, ndc0.y), centre), sidePlane(ndc1, vec2(ndc0.x, ndc1.y), centre));
  for (int i = int(local); builds && i < u_pointLightCount; i += 64) {
    const vec4 l = viewLight(i);
    bool visible = true;
    for (int p = 0; p < 4 && visible && l.w >= 0.0; ++p) visible = dot(planes[p], l.xyz) >= -l.w;
    if (visible) {
      const uint slot = atomicAdd(s_count, 1u);
      if (slot < uint(MAX_TILE_CANDIDATES)) {
        s_index[slot] = uint(i);
        s_light[slot] = l;
      }
    }
  }
  barrier();
  const bool candidates = s_count <= uint(MAX_TILE_CANDIDATES);
  const int tested = candidates ? int(s_count) : u_pointLightCount;

  for (int slice = int(local); builds && slice < SLICES; slice += 64) {
    // The cluster's box: the tile's corner rays between the slice's depths,
    // with a little depth slack so that a pixel whose slice rounds to this
    // cluster is inside it.
    const vec2 depth = clusterDepthRange(slice) * vec2(0.999, 1.001);
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int i = 0; i < 8; ++i) {
      const vec3 p = rayPoint(vec2((i & 1) != 0 ? ndc1.x : ndc0.x, (i & 2) != 0 ? ndc1.y : ndc0.y),
                              (i & 4) != 0 ? depth.y : depth.x);
      lo = min(lo, p);
      hi = max(hi, p);
    }
    const int cluster = clusterIndex(tile, slice);
    const uint base = uint(clusterCount()) + uint(cluster) * uint(MAX_CLUSTER_LIGHTS);
    uint count = 0u;
    for (int j = 0; j < tested; ++j) {
      const vec4 l = candidates ? s_light[j] : viewLight(j);
      const vec3 d = l.xyz - clamp(l.xyz, lo, hi);
      const uint index = candidates ? s_index[j] : uint(j);
      if ((l.w < 0.0 || dot(d, d) <= l.w * l.w) && spotMayReachViewBox(lights[index], lo, hi)) {
        if (count < uint(MAX_CLUSTER_LIGHTS)) data[base + count] = index;
        ++count;
      }
    }
    data[cluster] = count;
    if (count > uint(MAX_CLUSTER_LIGHTS)) atomicAdd(overflowedClusters, 1u);
  }
}
