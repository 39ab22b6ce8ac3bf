// Pipeline config files (JSON). Loading has two steps so that plugins named
// in the config can be loaded before pass types are checked:
//   ConfigDocument doc = ConfigDocument::parseFile(path, diags);
//   ... load doc.plugins() into the registry ...
//   PipelineConfig pipe = doc.build(registry, diags);
// Every diagnostic carries file, line, column and JSON path of the value at fault.
// The format is documented in docs/pipeline-format.md.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/graph.h"
#include "rgraph/params.h"
#include "rgraph/sampler_state.h"

namespace rgraph {

class PassRegistry;
struct SlotDecl;

// A pass's "samplers" entry for one sampled slot: the slot's declared state
// (SlotDecl::sampler, or SamplerState{} when it declares none) with the keys
// the config gives applied.
struct SamplerOverride {
  std::string slot;
  SamplerState state;
  SourceLocation where;  // the slot's key in "samplers"
};

struct PipelineConfig {
  std::string file;
  int version = 1;
  std::vector<std::string> plugins;
  // Sub-pixel camera jitter: the number of Halton(2,3) phases (config key
  // "jitter"; 0: off). Scene passes see the jittered camera unless their
  // PassDecl::jitter is false.
  uint32_t jitterPhases = 0;
  GraphDesc graph;                 // passes in config order
  std::vector<ParamSet> params;    // one per graph.passes entry, defaults filled in
  // One per graph.passes entry (may be shorter: no overrides): the pass's
  // "samplers" overrides.
  std::vector<std::vector<SamplerOverride>> samplers;
};

// The sampler state pass `pass` samples `slot` with: its config override,
// else the slot's declared state; nullopt: the texture's own parameters.
// `where` (optional) is set to the override's location, or left alone.
std::optional<SamplerState> slotSamplerState(const PipelineConfig& pipeline, size_t pass, const SlotDecl& slot,
                                             SourceLocation* where = nullptr);

class ConfigDocument {
 public:
  ConfigDocument();
  ~ConfigDocument();
  ConfigDocument(ConfigDocument&&) noexcept;
  ConfigDocument& operator=(ConfigDocument&&) noexcept;

  // Malformed JSON or a missing file: a diagnostic with the parser's position; ok() is false.
  static ConfigDocument parseFile(const std::string& path, Diagnostics& diags);
  static ConfigDocument parseText(const std::string& text, const std::string& file, Diagnostics& diags);

  bool ok() const;
  const std::string& file() const;
  // The top-level "plugins" array (names or paths), with their locations.
  std::vector<std::string> plugins() const;
  SourceLocation pluginLocation(size_t index) const;

  // Checks the document against the pass declarations and builds the graph.
  // Problems are appended to diags; the result is usable only when no error was added.
  PipelineConfig build(const PassRegistry& registry, Diagnostics& diags) const;

  // Location of the value at a JSON pointer (e.g. "/passes/1/type");
  // falls back to the closest existing parent (whose pointer is then the
  // returned path).
  SourceLocation locate(const std::string& jsonPointer) const;
  // Location of the key of the object member at a JSON pointer (e.g.
  // "/passes/0/inputs/albedo" -> the opening quote of "albedo"); falls back
  // to locate() when the pointer names no object member.
  SourceLocation locateKey(const std::string& jsonPointer) const;
  // The string at a JSON pointer (e.g. "/passes/1/type"); nullopt when there
  // is none or it is not a string.
  std::optional<std::string> stringAt(const std::string& jsonPointer) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgraph
