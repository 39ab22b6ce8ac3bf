// Shared pieces of the rgraph command line: loading a pipeline file through
// the config loader and the registry, and printing diagnostics.
#pragma once

#include <optional>
#include <string>

#include "rgraph/config.h"
#include "rgraph/diagnostics.h"
#include "rgraph/graph.h"

namespace rgraph::cli {

// Exit codes: 0 success, 1 the user's input is invalid or a run failed.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;

// Parses and checks a pipeline file against the built-in pass types.
// Appends every problem to diags; returns nullopt when any is an error.
std::optional<PipelineConfig> loadPipeline(const std::string& path, Diagnostics& diags);

// Prints diagnostics to stderr, one `FILE:LINE:COL: error: PATH: message` line each.
void printDiagnostics(const Diagnostics& diags);
// Diagnostics as the JSON array `rgraph validate --json` prints.
std::string diagnosticsJson(const Diagnostics& diags);

// The pipeline used when `rgraph render` names none.
std::string defaultPipelinePath();

}  // namespace rgraph::cli
