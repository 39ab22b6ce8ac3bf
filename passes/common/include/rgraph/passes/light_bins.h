// The light bins of the compute lighting passes (shaders/tiled_bin.comp,
// shaders/include/tile_bins.glsl): per bin of tiles, the view-depth range of
// its pixels, the point lights whose sphere (times BIN_REACH) meets its
// frustum over that range, and with the far field the far field of the
// others at the bin's point. tiled_deferred's tiles cull their bin's list;
// clustered_deferred's far field (far_field) takes a cluster's far field
// from its bin's. The buffer layout, its size, the program and its dispatch
// are stated here once for both.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rgraph/gl/uniform.h"
#include "rgraph/pass.h"

namespace rgraph::lighting {

struct BinGrid {
  int tileSize = 16;    // pixels per tile side (the bins are aligned to tiles)
  int binTiles = 4;     // tiles per bin side
  bool farField = false;  // BIN_REACH 2: the lights within twice their radius are listed, the rest summed
  uint32_t binding = 1;   // the storage-buffer binding the bins are on
  int binPixels() const { return tileSize * binTiles; }
};

// The defines of every program that reads or writes the bins, but TILE_SIZE
// (the includer states it): BIN_TILES, MAX_BIN_LIGHTS, BIN_REACH, BIN_BINDING.
std::vector<std::string> binDefines(const BinGrid& g);
// tiled_bin.comp with `defines` (the pass's shading defines, TILE_SIZE, the
// far field's) and binDefines(g).
ShaderProgramSpec binProgram(std::vector<std::string> defines, const BinGrid& g);

// The bin buffer and its dispatch.
class LightBins {
 public:
  LightBins() = default;
  LightBins(const LightBins&) = delete;
  LightBins& operator=(const LightBins&) = delete;
  ~LightBins();
  // (Re)creates the buffer for a target of `size`; `program` is binProgram's.
  void setup(uint32_t program, const BinGrid& g, Extent size);
  // Binds the buffer on g.binding and, with lights, dispatches the bins
  // (the scene's frame and point lights bound) and issues the storage barrier
  // for the lighting program that reads them.
  void build(int lights, Extent size) const;

 private:
  uint32_t program_ = 0, buffer_ = 0;
  BinGrid grid_;
  gl::Uniform lightCount_;
};

}  // namespace rgraph::lighting
