// The cluster grid shared by clustered_build.comp, which builds the lists,
// and the passes that read them (clustered_deferred.comp, forward_lit.frag):
// screen tiles of TILE_SIZE pixels times SLICES depth slices spaced
// exponentially from the camera's near to its far plane (both read from
// u_proj), so that a cluster's depth extent grows with its distance like its
// width does. Needs include/frame.glsl first.
// The list buffer (storage buffer 1): a header (clusters that overflowed this
// frame, then the grid it was built with: tile size, slices, list length),
// one count per cluster (every light that reaches it, also past
// MAX_CLUSTER_LIGHTS), then MAX_CLUSTER_LIGHTS light indices per cluster (in
// the order of what the build culled, the light bin's list or the lights',
// whatever the scheduling; a cut list keeps the first).
// The builder (CLUSTER_LISTS_BUILD) takes the grid from its defines and the
// pass that dispatches it writes the header; readers take the grid from the
// header, so that it is stated once, by the pass that builds the lists
// (passes/common/cluster_lists.cpp); a reader of the lists its own pass
// built may take the grid from the same defines (CLUSTER_GRID_DEFINES:
// clustered_far.comp, whose shared arrays need it at compile time).
#ifdef CLUSTER_LISTS_BUILD
layout(std430, binding = 1) buffer Clusters {
#else
layout(std430, binding = 1) readonly buffer Clusters {
#endif
  uint overflowedClusters;
  uint clusterGrid[3];  // tile size, slices, list length (MAX_CLUSTER_LIGHTS) the lists were built with
  uint data[];          // counts[clusterCount()], then indices[clusterCount() * MAX_CLUSTER_LIGHTS]
};

#if defined(CLUSTER_LISTS_BUILD) || defined(CLUSTER_GRID_DEFINES)
#ifndef TILE_SIZE
#define TILE_SIZE 32
#endif
#ifndef SLICES
#define SLICES 24
#endif
#ifndef MAX_CLUSTER_LIGHTS
#define MAX_CLUSTER_LIGHTS 256
#endif
#else
#define TILE_SIZE int(clusterGrid[0])
#define SLICES int(clusterGrid[1])
#define MAX_CLUSTER_LIGHTS int(clusterGrid[2])
#endif

ivec2 clusterTiles() { return (ivec2(u_viewport.xy) + TILE_SIZE - 1) / TILE_SIZE; }
int clusterCount() { return clusterTiles().x * clusterTiles().y * SLICES; }

// Near and far distances of the perspective projection (glm::perspective:
// P[2][2] = -(f+n)/(f-n), P[3][2] = -2fn/(f-n)).
vec2 clusterNearFar() {
  const float a = u_proj[2][2], b = u_proj[3][2];
  return vec2(b / (a - 1.0), b / (a + 1.0));
}

// The slice a positive view depth falls in (depths outside near..far clamp
// to the first or last slice).
int clusterSlice(float viewDepth) {
  const vec2 nf = clusterNearFar();
  const float t = log(max(viewDepth, nf.x) / nf.x) / log(nf.y / nf.x);
  return clamp(int(floor(t * float(SLICES))), 0, SLICES - 1);
}

// A slice's depth range [near (far/near)^(k/S), near (far/near)^((k+1)/S)].
vec2 clusterDepthRange(int slice) {
  const vec2 nf = clusterNearFar();
  const float ratio = nf.y / nf.x;
  return nf.x * vec2(pow(ratio, float(slice) / float(SLICES)), pow(ratio, float(slice + 1) / float(SLICES)));
}

// false when the bound list buffer is too small for this viewport's grid (a
// target smaller than the viewport; the passes' checks refuse a buffer too
// small for the target) or, for a reader, holds no grid: then no list is
// built and every pixel shades every light.
bool clusterListsFit(uint bufferUints) {
  return TILE_SIZE > 0 && SLICES > 0 && uint(clusterCount()) * uint(1 + MAX_CLUSTER_LIGHTS) <= bufferUints;
}

int clusterIndex(ivec2 tile, int slice) {
  const ivec2 tiles = clusterTiles();
  return (slice * tiles.y + tile.y) * tiles.x + tile.x;
}

// The cluster of the pixel `px` at positive view depth `viewDepth`; a pixel
// past the grid (a target larger than the viewport) takes the edge tile's.
int clusterAt(ivec2 px, float viewDepth) {
  return clusterIndex(min(px / TILE_SIZE, clusterTiles() - 1), clusterSlice(viewDepth));
}
