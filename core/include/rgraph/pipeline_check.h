// Everything `rgraph validate` checks once a pipeline is loaded, in one call:
// the graph compiled (rgraph/graph.h), the pass types' check hooks
// (rgraph/pass_check.h) and the glslang shader checks (rgraph/shader_check.h,
// optionally cached on disk: rgraph/shader_check_cache.h). The command line
// (validate, plan, render before any GL work) and rgraph/testing.h call it,
// so that they refuse exactly the same pipelines. GL-free.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/graph.h"

namespace rgraph {

struct PipelineConfig;
class PassRegistry;

enum class ShaderCheckMode {
  skip,    // no glslang
  run,     // compile and reflect every enabled pass's programs
  cached,  // the same, remembered in defaultShaderCheckCacheDir() (rgraph/shader_check_cache.h)
};

struct PipelineCheckOptions {
  // The pass types' check hooks and needsScene (runPassChecks).
  bool passChecks = true;
  ShaderCheckMode shaders = ShaderCheckMode::run;
  // Whether the pipeline runs with a scene; nullopt: unknown (see PassCheckOptions).
  std::optional<bool> scenePresent;
  // The pass types; nullptr: processRegistry() (rgraph/pipeline_load.h).
  const PassRegistry* registry = nullptr;
  // Shader folders searched before defaultShaderSearchDirectories() (which
  // already holds the process's --shader-path folders and loaded plugins' folders).
  std::vector<std::string> shaderDirectories;
};

// Compiles `pipeline.graph` with `compile`, then runs the checks `options`
// asks for. Appends every diagnostic (graph, pass checks, shaders, in that
// order) to `diags` and returns the plan. The pass and shader checks run even
// when the graph has errors: bindings the graph could not resolve only skip
// the checks that need them.
Plan checkPipeline(const PipelineConfig& pipeline, const CompileOptions& compile, const PipelineCheckOptions& options,
                   Diagnostics& diags);

}  // namespace rgraph
