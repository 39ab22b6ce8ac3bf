// The hazard harness (issue 31): a pipeline run plain and under each hazard
// mode (rgraph/hazards.h), every frame's kept resources (the output, imported
// textures, history sources, persistent resources) compared with the plain
// run's. A difference is a hazard: the pipeline's image depends on something
// its graph does not promise. It is reported at the first pass (in the plain
// order) after which a resource it could see differs, with the mode, the
// resource and subresource, the pixel count and where the pass is in the
// pipeline's JSON. `rgraph check-hazards` and testing::expectHazardFree
// (rgraph/testing.h) run it; docs/testing.md says what each mode catches.
//
// Comparison: bit-exact (NaN equal to the same NaN), by default for every
// format: one device runs the same draws on the same data in every mode, so
// a correct pipeline gives the same bits (Mesa llvmpipe, the CI's device, is
// deterministic). Multisampled textures are compared sample by sample (a
// pixel differs when any of its samples does). HazardCheckOptions::floatTolerance allows an absolute
// difference in float formats for devices that are not (a GPU's atomics
// may sum in another order).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/hazards.h"
#include "rgraph/renderer.h"

namespace rgraph {

struct HazardCheckOptions {
  // The scene (RenderScene::load's spec); "" renders without one.
  std::string scene = "learnopengl:overview";
  Extent size{64, 64};
  // Frames per run: history resources are compared over several (a frame
  // N image must not depend on aliasing at frame N-1).
  uint32_t frames = 3;
  // The modes, each run on its own; reorder runs seeded orders 1..reorder.
  HazardModes modes = HazardModes{0x3Fu, 3};
  // The registry, plugin and shader folders (size and hazards are set per run).
  RendererOptions renderer;
  // Absolute difference allowed in float formats (0: bit-exact); see the top.
  float floatTolerance = 0.0f;
};

struct HazardFinding {
  std::string mode;  // "poison", "reorder:2", ...
  uint32_t frame = 0;
  std::string pass, passType;  // empty when no pass is to blame (a difference only after the last pass)
  SourceLocation where;        // the pass in the pipeline's JSON
  std::string resource;        // with its subresource ("bloom.mip[2]", "shadow.layer[1]")
  bool declared = true;        // the pass declares writing the resource
  size_t pixels = 0, comparedPixels = 0;  // differing texels, and texels of that subresource
  // One line: `FILE:LINE:COL: error: hazard (MODE, frame F): ...`.
  std::string message;
};

struct HazardModeRun {
  std::string mode;
  size_t comparedPixels = 0;  // texels compared over every frame (kept resources and pass outputs)
  // Differences in intermediate resources with no effect on any kept one.
  size_t hiddenDifferences = 0;
  std::vector<HazardFinding> findings;  // the first finding, if any
};

struct HazardReport {
  std::string pipeline;
  std::string error;  // the plain run failed (nothing compared)
  std::vector<HazardModeRun> runs;
  bool hazardFree() const;
  std::vector<HazardFinding> findings() const;
  // A table (mode, compared pixels, finding) and each finding's message.
  std::string describe() const;
};

// Needs a current GL 4.5 context. Never throws for a bad pipeline: the plain
// run's failure is HazardReport::error.
HazardReport checkHazards(const std::string& pipelinePath, const HazardCheckOptions& options = {});

}  // namespace rgraph
