#include "rgraph/pipeline_load.h"

#include <filesystem>
#include <optional>
#include <nlohmann/json.hpp>

#include "rgraph/error.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"

namespace rgraph {

PassRegistry& processRegistry() {
  static PassRegistry registry = PassRegistry::builtins();
  return registry;
}

PluginLoader& processPluginLoader() {
  static PluginLoader loader(processRegistry());
  return loader;
}

namespace {

// "unknown pass type 'ssao'" when librgraph_ssao.so is on the plugin search
// path: say which plugin has it and what to add to the config (instead of a
// "did you mean" spelling: the type exists, only not loaded).
void suggestPlugins(const ConfigDocument& doc, const PluginLoader& loader, Diagnostics& diags, size_t from) {
  const bool hasPlugins = !doc.plugins().empty();
  for (size_t i = from; i < diags.size(); ++i) {
    Diagnostic& d = diags[i];
    if (d.code != DiagCode::unknown_pass_type) continue;
    const std::optional<std::string> type = doc.stringAt(d.where.path);
    if (!type) continue;
    const std::optional<PluginLoader::Provider> provider = loader.findProvider(*type);
    if (!provider) continue;
    const std::string entry = nlohmann::json(provider->name).dump();
    if (const size_t guess = d.message.find(" (did you mean"); guess != std::string::npos) d.message.erase(guess);
    d.message += "; plugin " + entry + " (" + provider->path + ") provides it: " +
                 (hasPlugins ? "add " + entry + " to the config's \"plugins\" array"
                             : "add \"plugins\": [" + entry + "] at the top level of the config");
  }
}

std::optional<PipelineConfig> finishLoad(const ConfigDocument& doc, const std::string& baseDir,
                                         const PipelineLoadOptions& options, Diagnostics& diags) {
  if (!doc.ok() || hasErrors(diags)) return std::nullopt;
  PassRegistry& registry = options.registry ? *options.registry : processRegistry();
  // A registry without a loader: one for this load, bound to it (the
  // process's loader would register the plugins elsewhere).
  std::optional<PluginLoader> own;
  if (!options.loader && options.registry) own.emplace(registry);
  PluginLoader& loader = options.loader ? *options.loader : own ? *own : processPluginLoader();
  for (const auto& dir : options.pluginDirectories) loader.addSearchDirectory(dir);
  // Plugins before the pass types are checked.
  const std::vector<std::string> plugins = doc.plugins();
  for (size_t i = 0; i < plugins.size(); ++i) {
    std::string error;
    if (loader.load(plugins[i], baseDir, error)) continue;
    Diagnostic d;
    d.code = DiagCode::plugin_error;
    d.message = error;
    d.where = doc.pluginLocation(i);
    diags.push_back(std::move(d));
  }
  if (hasErrors(diags)) return std::nullopt;
  const size_t before = diags.size();
  PipelineConfig pipeline = doc.build(registry, diags);
  suggestPlugins(doc, loader, diags, before);
  if (hasErrors(diags)) return std::nullopt;
  return pipeline;
}

PipelineConfig orThrow(std::optional<PipelineConfig> pipeline, const Diagnostics& diags, const std::string& name) {
  if (pipeline) return std::move(*pipeline);
  std::string msg = name + " has errors:";
  for (const auto& d : diags) msg += "\n  " + formatDiagnostic(d);
  throw RuntimeError(msg);
}

}  // namespace

PipelineConfig loadPipelineFileOrThrow(const std::string& path, const PipelineLoadOptions& options) {
  Diagnostics diags;
  std::optional<PipelineConfig> p = loadPipelineFile(path, options, diags);
  return orThrow(std::move(p), diags, path);
}

PipelineConfig loadPipelineTextOrThrow(std::string_view json, const std::string& nameForMessages,
                                       const PipelineLoadOptions& options) {
  Diagnostics diags;
  std::optional<PipelineConfig> p = loadPipelineText(json, nameForMessages, {}, options, diags);
  return orThrow(std::move(p), diags, nameForMessages);
}

std::optional<PipelineConfig> loadPipelineFile(const std::string& path, const PipelineLoadOptions& options,
                                               Diagnostics& diags) {
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  std::error_code ec;
  const std::string base = std::filesystem::absolute(path, ec).parent_path().string();
  return finishLoad(doc, base, options, diags);
}

std::optional<PipelineConfig> loadPipelineText(std::string_view json, const std::string& nameForMessages,
                                               const std::string& baseDir, const PipelineLoadOptions& options,
                                               Diagnostics& diags) {
  ConfigDocument doc = ConfigDocument::parseText(std::string(json), nameForMessages, diags);
  std::string base = baseDir;
  if (base.empty()) {
    std::error_code ec;
    base = std::filesystem::current_path(ec).string();
  }
  return finishLoad(doc, base, options, diags);
}

}  // namespace rgraph
