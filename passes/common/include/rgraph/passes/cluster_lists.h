// Clustered light lists (shaders/include/clusters.glsl): the grid
// parameters, the list buffer's size, the build program and its dispatch,
// and the storage-buffer slot through which other passes read the lists.
// The cluster_lights pass builds them into a graph buffer that
// clustered_deferred, forward and forward_lit read (built once a frame for
// all of them); clustered_deferred builds its own when that slot is unbound.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rgraph/gl/uniform.h"
#include "rgraph/pass.h"

namespace rgraph::clusters {

// The storage-buffer binding the lists are on (the point lights are on 0).
constexpr uint32_t kBinding = 1;
// The slot a pass reads the lists through.
constexpr const char* kSlot = "clusters";

struct Grid {
  int tileSize = 32;  // pixels
  int slices = 24;    // exponential depth slices from near to far
  int maxLights = 256;  // light indices one cluster's list holds
};

// tile_size (default `defaultTileSize`), slices, max_cluster_lights.
std::vector<ParamDecl> gridParams(int defaultTileSize = 32);
Grid grid(const ParamSet& params);
// The list buffer for `g` over a viewport of `size`: header, counts, lists.
uint64_t bufferBytes(const Grid& g, Extent size);
// The grid as defines (TILE_SIZE, SLICES, MAX_CLUSTER_LIGHTS): the build
// program's, and those of a program that reads lists its own pass built
// (CLUSTER_GRID_DEFINES in include/clusters.glsl).
std::vector<std::string> gridDefines(const ParamSet& params);
// The build program (clustered_build.comp with the grid's defines and a
// test's invocation permutation, rgraph/passes/invocation_order.h).
ShaderProgramSpec buildProgram(const ParamSet& params);
// The build program of a pass that reads the G-buffer and builds lists for
// its own pixels only (clustered_deferred): CLUSTER_DEPTH_BOUNDS bounds each
// cluster's box by its pixels' depths (a cluster without pixels lists
// nothing), so that a cluster's list holds what reaches its pixels, not its
// whole depth slice; each tile culls the list of its light bin
// (rgraph/passes/light_bins.h, `binDefines`) instead of every light. With the
// pass's shading defines and G-buffer samplers.
ShaderProgramSpec depthBoundedBuildProgram(const ParamSet& params, std::vector<std::string> binDefines);

// The optional storage_read slot of a pass that shades with the lists, and
// its check (bound: a buffer, not a texture).
SlotDecl readerSlot(std::string description);
void checkReaderSlot(const PassCheckContext& ctx, PassChecks& checks);
// The builder's check: its slot holds the lists of its grid at the plan's
// output size (the message says how many bytes are needed).
void checkBuilderSlot(const PassCheckContext& ctx, PassChecks& checks, const std::string& slot);

// Records the build: writes the header (overflow counter zeroed, the grid),
// binds the buffer on kBinding and the scene's point lights at `threshold`
// on 0, and dispatches a group per tile (none without lights). `barrier`:
// issue the storage barrier for the reader that follows in the same pass.
class Builder {
 public:
  Builder() = default;
  explicit Builder(uint32_t program);
  void build(GpuScene& scene, uint32_t buffer, const Grid& g, Extent size, int lights, float threshold,
             bool barrier) const;

 private:
  uint32_t program_ = 0;
  gl::Uniform lightCount_;
};

}  // namespace rgraph::clusters
