// Shared pieces of the rgraph command line: loading a pipeline file through
// the config loader and the registry, and printing diagnostics.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/diagnostics.h"
#include "rgraph/gl/context.h"
#include "rgraph/graph.h"
#include "rgraph/pipeline_check.h"
#include "rgraph/renderer.h"

namespace rgraph {
class PassRegistry;
class PluginLoader;
}  // namespace rgraph

namespace rgraph::cli {

// Exit codes: 0 success, 1 the user's input is invalid or a run failed.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;

// The command line's pass types: a copy of PassRegistry::builtins() with the
// plugins --plugin and the pipeline loaded, and the loader bound to it
// (--plugin-path folders first). One command runs per process, so these are
// processRegistry() and processPluginLoader() (rgraph/pipeline_load.h), which
// the benchmarks' pipeline loads use too.
PassRegistry& registry();
PluginLoader& pluginLoader();
// Options for the Renderer of `render` and `view`: a copy of registry() (the
// renderer copies it) and the --plugin-path folders; the caller sets the rest.
RendererOptions rendererOptions();

// Parses a pipeline file, loads the plugins its "plugins" array names into
// registry() (a failure is a plugin_error diagnostic at the plugin's name in
// the file), then checks it against the registered types.
// Appends every problem to diags; returns nullopt when any is an error.
std::optional<PipelineConfig> loadPipeline(const std::string& path, Diagnostics& diags);

// Plugins. --plugin-path folders are searched before $RGRAPH_PLUGIN_PATH and
// rgraph's own plugin folder (see rgraph/plugin.h).
void addPluginSearchDirectory(const std::string& dir);
// Loads plugins named on the command line (names, or paths relative to the
// working directory). Prints `error: plugin 'NAME': reason` per failure;
// false when any failed.
bool loadPlugins(const std::vector<std::string>& namesOrPaths);

// --plugin-path and --shader-path: each must be an existing folder, else
// `error: OPTION 'DIR': no such folder` (or "not a folder") and false.
bool checkFolders(const std::string& option, const std::vector<std::string>& dirs);

// --shader-path folders (checkFolders first): searched before the built-in
// shaders by validate and render.
void addShaderPaths(const std::vector<std::string>& dirs);

// A RuntimeError's text as one message line: `FILE:LINE[:COL]: error: rest` when the text starts with a
// location (a scene file's `scene.json:2:1: invalid JSON ...`), else `error: text`.
std::string errorLine(const std::string& what);

// Prints diagnostics to stderr, one `FILE:LINE:COL: error: PATH: message` line each.
void printDiagnostics(const Diagnostics& diags);
// Diagnostics as the JSON array `rgraph validate --json` prints.
std::string diagnosticsJson(const Diagnostics& diags);

// A plan's "memory" object as `plan --json` and `render --stats` write it:
// naive_bytes, allocated_bytes, peak_live_bytes (Plan's fields of those names).
nlohmann::json memoryJson(const Plan& plan);

// The device a context runs on, as `render --stats` ("context") and `bench`
// (results.json's "machine") record it: vendor, renderer, version (GL_VENDOR,
// GL_RENDERER, GL_VERSION), platform, egl_device (its index, null when not on
// the device platform) and egl_device_description (null likewise).
nlohmann::json contextJson(const ContextDevice& device);

// Compile options for --width/--height and --max-texture-size (16384, the
// OpenGL 4.5 minimum, when not given), with the limit's origin for messages.
CompileOptions compileOptions(uint32_t width, uint32_t height, uint32_t maxTextureSize);

// What `validate` checks once a pipeline is loaded, and `render` before any
// GL work (so that render refuses what validate refuses): the graph compiled
// with these options, the pass types' check hooks (rgraph/pass_check.h) and,
// unless skipped, the glslang shader checks (rgraph/shader_check.h; `cached`
// remembers their results on disk, rgraph/shader_check_cache.h). Appends every
// diagnostic to diags and returns the plan.
// The body is rgraph::checkPipeline (rgraph/pipeline_check.h), shared with
// rgraph/testing.h; this adds the built-in registry and the CLI's defaults.
using ShaderChecks = ShaderCheckMode;
Plan checkPipeline(const PipelineConfig& pipeline, const CompileOptions& options, ShaderChecks shaders,
                   Diagnostics& diags, std::optional<bool> scenePresent = std::nullopt);

// The pipeline used when `rgraph render` names none.
std::string defaultPipelinePath();

}  // namespace rgraph::cli
