#include "rgraph/pipeline_check.h"

#include "rgraph/config.h"
#include "rgraph/pass_check.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/shader_check_cache.h"

namespace rgraph {

Plan checkPipeline(const PipelineConfig& pipeline, const CompileOptions& compileOptions,
                   const PipelineCheckOptions& options, Diagnostics& diags) {
  const PassRegistry& registry = options.registry ? *options.registry : processRegistry();
  Plan plan = compile(pipeline.graph, compileOptions);
  diags.insert(diags.end(), plan.diagnostics.begin(), plan.diagnostics.end());
  if (options.passChecks) {
    PassCheckOptions checkOptions;
    checkOptions.scenePresent = options.scenePresent;
    Diagnostics passDiags = runPassChecks(pipeline, plan, registry, checkOptions);
    diags.insert(diags.end(), passDiags.begin(), passDiags.end());
  }
  // Shader checks need no GL context: glslang compiles and reflects what each
  // enabled pass would build. They run even when the graph has errors (those
  // are already listed; bindings it could not resolve only skip the format checks).
  if (options.shaders != ShaderCheckMode::skip) {
    std::vector<std::string> dirs = options.shaderDirectories;
    for (auto& d : defaultShaderSearchDirectories()) dirs.push_back(std::move(d));
    ShaderChecker checker(std::move(dirs));
    const std::string cacheDir = options.shaders == ShaderCheckMode::cached ? defaultShaderCheckCacheDir() : "";
    CachedShaderCheck checked = checkPipelineCached(checker, pipeline, plan, registry, cacheDir);
    diags.insert(diags.end(), checked.diagnostics.begin(), checked.diagnostics.end());
  }
  return plan;
}

}  // namespace rgraph
