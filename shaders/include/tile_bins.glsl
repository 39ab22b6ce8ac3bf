// The light bins of tiled_deferred and of clustered_deferred's far field
// (passes/common/light_bins.cpp sizes and dispatches them): tiled_bin.comp lists, per bin of
// BIN_TILES x BIN_TILES tiles, the point lights whose sphere (radius times
// BIN_REACH) meets the bin's frustum over its pixels' depth range, so that
// each tile culls its bin's list instead of every light: the culling cost
// stays flat in the light count at constant overlap. With FAR_FIELD it also
// sums the far field of the lights it does not list, at the bin's point.
// Storage buffer 1: one record of BIN_RECORD uints per bin: the light count
// (every light listed, also past MAX_BIN_LIGHTS: then the tiles test every
// light), 3 unused, the point the far field was summed at (xyz floats, 1
// unused), FAR_FIELD_VALUES far-field floats (radiance, weighted direction,
// gradient, weighted offset per direction bin: far_field.glsl), then MAX_BIN_LIGHTS indices
// in increasing order (the first MAX_BIN_LIGHTS listed, whatever the scheduling).
// On storage-buffer binding BIN_BINDING: writable in tiled_bin.comp
// (BIN_WRITER), read-only in the programs that read the bins.
// Needs TILE_SIZE and include/frame.glsl first.
#ifndef BIN_TILES
#define BIN_TILES 4
#endif
#ifndef MAX_BIN_LIGHTS
#define MAX_BIN_LIGHTS 1024
#endif
#ifndef BIN_REACH
#define BIN_REACH 1.0
#endif
#ifndef BIN_BINDING
#define BIN_BINDING 1
#endif
#define BIN_PIXELS (TILE_SIZE * BIN_TILES)
#define BIN_HEADER 200  // 4 + 4 + far_field.glsl's FAR_FIELD_VALUES (192)
#define BIN_RECORD (BIN_HEADER + MAX_BIN_LIGHTS)

uvec2 binGrid() { return (uvec2(u_viewport.xy) + uint(BIN_PIXELS) - 1u) / uint(BIN_PIXELS); }
uint binRecord(uvec2 bin) { return (bin.y * binGrid().x + bin.x) * uint(BIN_RECORD); }
// false for a bin outside the viewport's grid or past the buffer's end (the
// pass sized the buffer for its target; a viewport larger than the target):
// then nothing is written there and the tiles test every light.
bool binFits(uvec2 bin, uint bufferUints) {
  return all(lessThan(bin, binGrid())) && binRecord(bin) + uint(BIN_RECORD) <= bufferUints;
}

#ifdef BIN_WRITER
layout(std430, binding = BIN_BINDING) writeonly buffer Bins { uint bins[]; };
#else
layout(std430, binding = BIN_BINDING) readonly buffer Bins { uint bins[]; };

// The point a bin's far field was summed at, and its direction bin b
// (radiance, weighted direction, gradient, weighted offsets: far_field.glsl's sums).
vec3 binFarFieldPoint(uint record) { return uintBitsToFloat(uvec3(bins[record + 4u], bins[record + 5u], bins[record + 6u])); }
void binFarField(uint record, uint b, out vec3 v[4]) {
  for (uint j = 0u; j < 4u; ++j)
    for (uint c = 0u; c < 3u; ++c) v[j][c] = uintBitsToFloat(bins[record + 8u + (4u * b + j) * 3u + c]);
}
#endif
