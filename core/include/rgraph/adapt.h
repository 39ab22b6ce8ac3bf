// "Model no more than a scene needs": given what a scene contains, each pass
// type's adapt hook may disable its pass or drop optional targets, before the
// graph is compiled; the compiler then culls and aliases the rest.
#pragma once

#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/graph.h"
#include "rgraph/pass.h"

namespace rgraph {

class PassRegistry;

struct AdaptReport {
  std::vector<std::string> notes;  // "pass 'x': ..." one line per change
  struct Table {
    std::string pass;                // the pass (template) whose hook made it
    std::vector<std::string> lines;  // PassAdaptation::report
  };
  std::vector<Table> tables;
};

// Applies every pass type's adapt hook to the pipeline in place.
AdaptReport adaptToScene(PipelineConfig& pipeline, const PassRegistry& registry, const SceneFeatures& features);

// Bytes per pixel of the G-buffer: every attachment a live pass writes
// through a slot its type declares a G-buffer target (SlotDecl::gbufferTarget)
// and whose resource is used, at the output resolution.
uint32_t gbufferBytesPerPixel(const PipelineConfig& pipeline, const Plan& plan, const PassRegistry& registry);

}  // namespace rgraph
