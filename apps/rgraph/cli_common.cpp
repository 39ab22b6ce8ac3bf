#include "cli_common.h"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <regex>
#include <nlohmann/json.hpp>

#include "rgraph/own_files.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"

namespace rgraph::cli {

namespace {
std::vector<std::string>& pluginDirectories() {
  static std::vector<std::string> dirs;
  return dirs;
}
}  // namespace

// One command per process: the process's registry is the command's.
PassRegistry& registry() { return processRegistry(); }
PluginLoader& pluginLoader() { return processPluginLoader(); }

void addPluginSearchDirectory(const std::string& dir) {
  pluginDirectories().push_back(dir);
  pluginLoader().addSearchDirectory(dir);
}

RendererOptions rendererOptions() {
  RendererOptions options;
  options.registry = &registry();
  options.pluginDirectories = pluginDirectories();
  return options;
}

bool loadPlugins(const std::vector<std::string>& namesOrPaths) {
  bool ok = true;
  std::error_code ec;
  const std::string cwd = std::filesystem::current_path(ec).string();
  for (const auto& name : namesOrPaths) {
    std::string error;
    if (!pluginLoader().load(name, cwd, error)) {
      std::cerr << "error: " << error << "\n";
      ok = false;
    }
  }
  return ok;
}

std::optional<PipelineConfig> loadPipeline(const std::string& path, Diagnostics& diags) {
  PipelineLoadOptions options;
  options.registry = &registry();
  options.loader = &pluginLoader();
  return loadPipelineFile(path, options, diags);
}

bool checkFolders(const std::string& option, const std::vector<std::string>& dirs) {
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec)) continue;
    const bool exists = std::filesystem::exists(dir, ec);
    std::cerr << "error: " << option << " '" << dir << "': " << (exists ? "not a folder" : "no such folder") << "\n";
    return false;
  }
  return true;
}

void addShaderPaths(const std::vector<std::string>& dirs) {
  for (const auto& dir : dirs) {
    std::error_code ec;
    addShaderSearchDirectory(std::filesystem::absolute(dir, ec).lexically_normal().string());
  }
}

CompileOptions compileOptions(uint32_t width, uint32_t height, uint32_t maxTextureSize) {
  CompileOptions o;
  o.output = Extent{width, height};
  if (maxTextureSize > 0) {
    o.maxTextureSize = maxTextureSize;
    o.maxTextureSizeOrigin = "the limit --max-texture-size sets";
  } else {
    o.maxTextureSizeOrigin =
        "the GL_MAX_TEXTURE_SIZE every OpenGL 4.5 device reaches (--max-texture-size N sets another limit)";
  }
  return o;
}

Plan checkPipeline(const PipelineConfig& pipeline, const CompileOptions& options, ShaderChecks shaders,
                   Diagnostics& diags, std::optional<bool> scenePresent) {
  PipelineCheckOptions checks;
  checks.registry = &registry();
  checks.shaders = shaders;
  checks.scenePresent = scenePresent;
  return rgraph::checkPipeline(pipeline, options, checks, diags);
}

void printDiagnostics(const Diagnostics& diags) {
  for (const auto& d : diags) std::cerr << formatDiagnostic(d) << "\n";
}

std::string diagnosticsJson(const Diagnostics& diags) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& d : diags) {
    out.push_back({{"severity", severityName(d.severity)},
                   {"code", diagCodeName(d.code)},
                   {"message", d.message},
                   {"file", d.where.file},
                   {"line", d.where.line},
                   {"column", d.where.column},
                   {"path", d.where.path},
                   {"pass", d.pass},
                   {"slot", d.slot},
                   {"resource", d.resource}});
  }
  return out.dump(2);
}

std::string defaultPipelinePath() {
  const std::string name = "default.json";
  // $RGRAPH_PIPELINE_DIR, else rgraph's own pipelines: an install's
  // share/rgraph/pipelines found from librgraph's location, a build tree's
  // source pipelines/ (rgraph/own_files.h). The last candidate is the one
  // named in the "cannot read" message when none has the file.
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("RGRAPH_PIPELINE_DIR")) candidates.emplace_back(env);
  candidates.emplace_back(ownFiles().pipelines);
  for (const auto& dir : candidates) {
    std::error_code ec;
    if (std::filesystem::exists(dir / name, ec)) return (dir / name).lexically_normal().string();
  }
  return (candidates.back() / name).lexically_normal().string();
}

nlohmann::json memoryJson(const Plan& plan) {
  return {{"naive_bytes", plan.naiveBytes},
          {"allocated_bytes", plan.allocatedBytes},
          {"peak_live_bytes", plan.peakLiveBytes}};
}

nlohmann::json contextJson(const ContextDevice& device) {
  const bool onDevice = device.eglDevice >= 0;
  return {{"vendor", device.vendor},
          {"renderer", device.renderer},
          {"version", device.version},
          {"platform", device.platform},
          {"egl_device", onDevice ? nlohmann::json(device.eglDevice) : nlohmann::json()},
          {"egl_device_description", onDevice ? nlohmann::json(device.eglDeviceDescription) : nlohmann::json()}};
}

std::string errorLine(const std::string& what) {
  static const std::regex located(R"(^([^:\s][^:\n]*:[0-9]+(:[0-9]+)?): )");
  std::smatch m;
  if (!std::regex_search(what, m, located)) return "error: " + what;
  const std::string rest = what.substr(size_t(m.length(0)));
  return rest.rfind("error: ", 0) == 0 ? what : m[1].str() + ": error: " + rest;
}

}  // namespace rgraph::cli
