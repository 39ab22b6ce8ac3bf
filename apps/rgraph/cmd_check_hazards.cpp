// `rgraph check-hazards`: the hazard harness (rgraph/hazard_check.h) on one
// pipeline, in a headless context: a table of modes and compared pixels, the
// findings as `FILE:LINE:COL: error: ...` lines; exit 1 on a finding.
#include <iostream>

#include "cli_common.h"
#include "commands.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/hazard_check.h"

namespace rgraph::cli {

int runCheckHazards(const CheckHazardsOptions& options) {
  HazardCheckOptions check;
  if (!options.hazards.empty()) {
    const std::string error = parseHazardModes(options.hazards, check.modes);
    if (!error.empty()) {
      std::cerr << "error: --hazards: " << error << "\n";
      return kExitFailure;
    }
    if (!check.modes.any()) {
      std::cerr << "error: --hazards: no mode given\n";
      return kExitFailure;
    }
  }
  check.scene = options.scene.empty() ? std::string("learnopengl:overview") : options.scene;
  check.size = Extent{options.size.width, options.size.height};
  check.frames = options.frames;
  check.renderer = cli::rendererOptions();
  check.renderer.maxTextureSize = options.size.maxTextureSize;
  const std::string path = options.pipeline.empty() ? defaultPipelinePath() : options.pipeline;
  HazardReport report;
  try {
    auto context = GlContext::create();
    report = checkHazards(path, check);
  } catch (const RuntimeError& e) {
    std::cerr << errorLine(e.what()) << "\n";
    return kExitFailure;
  }
  if (!report.error.empty()) {
    std::cerr << report.error << "\n";
    return kExitFailure;
  }
  std::cout << "hazard check of " << path << " on " << check.scene << " at " << check.size.width << "x"
            << check.size.height << ", " << check.frames << (check.frames == 1 ? " frame" : " frames") << "\n";
  for (const HazardModeRun& r : report.runs)
    std::cout << "  " << r.mode << ": " << r.comparedPixels << " pixels compared: "
              << (r.findings.empty() ? "no finding" : "HAZARD") << "\n";
  for (const HazardFinding& f : report.findings()) std::cerr << f.message << "\n";
  return report.hazardFree() ? kExitOk : kExitFailure;
}

}  // namespace rgraph::cli
