// Loading a pipeline config the one way every front end does it (the CLI,
// rgraph/renderer.h, rgraph/testing.h): parse, load the plugins its "plugins"
// array names into the registry, then check it against the registered pass
// types. GL-free.
//
//   Diagnostics diags;
//   std::optional<PipelineConfig> p = loadPipelineFile("pipelines/default.json", {}, diags);
//   if (!p) for (auto& d : diags) std::cerr << formatDiagnostic(d) << "\n";
//
// Config problems never throw: each is a Diagnostic with file:line:col and the
// JSON path (a plugin that fails to load is a plugin_error at its name in
// "plugins"). Only allocation failure escapes as an exception.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/diagnostics.h"

namespace rgraph {

class PassRegistry;
class PluginLoader;

struct PipelineLoadOptions {
  // Folders searched for plugin names before $RGRAPH_PLUGIN_PATH and
  // rgraph's own plugin folder (rgraph/plugin.h).
  std::vector<std::string> pluginDirectories;
  // The pass types the pipeline may name, and the loader that loads its
  // plugins into that registry (bound to it). A registry without a loader:
  // a loader of its own for the one call. Neither: processRegistry() and
  // processPluginLoader(), shared by the whole process. Renderer,
  // rgraph/testing.h and the command line always pass their own.
  PassRegistry* registry = nullptr;
  PluginLoader* loader = nullptr;
};

// The pipeline in a file. Plugin paths in "plugins" are relative to its folder.
std::optional<PipelineConfig> loadPipelineFile(const std::string& path, const PipelineLoadOptions& options,
                                               Diagnostics& diags);
// The pipeline in JSON text. Messages name `nameForMessages` (e.g. "<inline>");
// plugin paths are relative to `baseDir` ("" = the working directory).
std::optional<PipelineConfig> loadPipelineText(std::string_view json, const std::string& nameForMessages,
                                               const std::string& baseDir, const PipelineLoadOptions& options,
                                               Diagnostics& diags);

// The same for programs whose pipelines must be valid (benchmarks, tests):
// throws RuntimeError "<file> has errors:" followed by one formatDiagnostic
// line per diagnostic.
PipelineConfig loadPipelineFileOrThrow(const std::string& path, const PipelineLoadOptions& options = {});
PipelineConfig loadPipelineTextOrThrow(std::string_view json, const std::string& nameForMessages,
                                       const PipelineLoadOptions& options = {});

// The registry and loader the functions above use when the options name none:
// a copy of PassRegistry::builtins() made at first use, and every plugin
// loaded through them since (one per process: what one caller loads, every
// later one sees). For programs that load known pipelines (rgraph's own
// benchmarks and tests); an application or a test suite of its own gives
// each Renderer or compile its own registry instead (rgraph/registry.h).
PassRegistry& processRegistry();
PluginLoader& processPluginLoader();

}  // namespace rgraph
