// The shader checks of a whole pipeline (ShaderChecker::checkPipeline),
// remembered on disk so that `rgraph render`, which runs them before every
// render, pays for glslang only when something they depend on changed.
//
// The key is a hash of everything the result depends on: the pipeline (passes,
// types, params, bindings and their locations, resources), the expanded text
// of every shader each enabled pass's programs(params) names with its
// defines, the shader search folders, the working directory (messages show
// shader paths relative to it), and the identity (path, size, modification
// time) of the running executable and of every plugin file whose pass types
// the pipeline uses (their code decides the programs and the checks).
// An entry is a verdict, not a result to replay: only checks that found
// nothing are remembered (a hit returns no diagnostics), so a crafted entry
// can make rgraph print nothing; a check that found something runs again
// every time. Entries are written to a temporary file and renamed into place,
// so concurrent runs never see a partial entry; an entry that is not exactly
// what rgraph writes for this key (damaged, foreign, another hash, not a
// regular file: a FIFO is never opened for blocking reads) is a miss, and is
// rewritten when the checks pass. No GL.
#pragma once

#include <string>

#include "rgraph/diagnostics.h"

namespace rgraph {

struct PipelineConfig;
struct Plan;
class PassRegistry;
class ShaderChecker;

// $RGRAPH_CACHE_DIR, else $XDG_CACHE_HOME/rgraph, else $HOME/.cache/rgraph,
// with /shadercheck appended; "" when none is set (no caching).
std::string defaultShaderCheckCacheDir();

struct CachedShaderCheck {
  Diagnostics diagnostics;  // always empty on a hit
  bool hit = false;  // the cache says these checks found nothing; glslang not run
};

// ShaderChecker::checkPipeline through the cache in `cacheDir` ("" : no cache,
// checks run every time). A cache that cannot be read or written is skipped
// silently: the checks then run as without it.
CachedShaderCheck checkPipelineCached(ShaderChecker& checker, const PipelineConfig& pipeline, const Plan& plan,
                                      const PassRegistry& registry, const std::string& cacheDir);

}  // namespace rgraph
