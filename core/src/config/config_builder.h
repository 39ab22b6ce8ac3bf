// Internal to the config loader: the Builder behind ConfigDocument::build,
// its member functions split by subject over three files:
//   config_build.cpp            the top level, duplicate keys, slot formats
//                               (checks across resources and passes, on the
//                               compiler's version resolution),
//                               ConfigDocument::build;
//   config_build_resources.cpp  resource declarations (type, format, size,
//                               samples, mips, clear, buffer size);
//   config_build_passes.cpp     passes, their bindings, slots and parameters;
//   config_build_samplers.cpp   a pass's "samplers" (sampler-state overrides).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "config_impl.h"
#include "config_values.h"
#include "rgraph/registry.h"

namespace rgraph::config_detail {

// Version or resource name -> index of its resource in the GraphDesc.
using VersionResources = std::unordered_map<std::string_view, size_t>;

// One "inputs"/"outputs" entry that holds a usable name.
struct Binding {
  std::string name;     // the resource or version, without its subresource
  std::string pointer;  // of the string value
  Subresource sub;      // ".mip[2]", ".layer[3]", ".face[+x]": whole when none
};

struct PassInfo {
  std::string pointer;  // "/passes/3"
  std::string label;    // "pass 'lighting' (type deferred_lighting)"
  const PassTypeDesc* type = nullptr;
  bool hasInputs = false, hasOutputs = false;
  std::map<std::string, Binding> inputs, outputs;  // slot -> binding (string values only)
  // Every key present, even with a rejected value: such a slot counts as
  // bound, so that a bad value is not also reported as a missing slot.
  std::set<std::string> inputKeys, outputKeys;
  // Typos already reported with a suggestion ("outputz" for "outputs", slot
  // "colour" for "color"): what they were meant to bind is not also missing.
  bool inputsTypo = false, outputsTypo = false;
  std::set<std::string> slotTypos;
};

class Builder {
 public:
  Builder(const ConfigDocument& doc, const Json& root, const config_detail::SourceMap& map,
          const PassRegistry& registry, Diagnostics& diags)
      : doc_(doc), root_(root), map_(map), registry_(registry), diags_(diags) {}
  PipelineConfig run();

 private:
  Diagnostic& error(DiagCode code, SourceLocation where, std::string message) {
    Diagnostic d;
    d.code = code;
    d.message = std::move(message);
    d.where = std::move(where);
    diags_.push_back(std::move(d));
    return diags_.back();
  }
  SourceLocation at(const std::string& pointer) const { return doc_.locate(pointer); }
  SourceLocation keyAt(const std::string& pointer) const { return doc_.locateKey(pointer); }

  void typeError(const std::string& pointer, const std::string& expected, const Json& got) {
    error(DiagCode::config_schema, at(pointer), "expected " + expected + ", got " + jsonTypeName(got));
  }

  // config_build.cpp
  std::set<std::string> checkKeys(const Json& object, const std::string& pointer,
                                  const std::vector<std::string>& allowed, const std::string& what);
  void reportDuplicateKeys();
  void checkTopLevel();
  void checkFormats(const VersionResources& versions);

  // config_build_resources.cpp
  void checkResources(const Json& resources);
  bool checkResource(const Json& res, const std::string& pointer, ResourceDecl& r);
  void inheritHistoryDescriptors(const Json& resources);
  void checkClear(const Json& clear, const std::string& pointer, bool formatOk, TextureDesc& t);
  void checkSize(const Json& size, const std::string& pointer, SizeSpec& out);

  // config_build_passes.cpp
  void checkPasses(const Json& passes);
  void checkPass(const Json& pass, PassInfo& info, std::map<std::string, std::string>& names, PassDecl& decl,
                 ParamSet& params);
  void loadedPart(const Binding& in, const Binding& out, const std::string& slot, const std::string& passName,
                  Subresource& sub);
  void readBindings(const Json* object, const std::string& pointer, PassInfo& info, const std::string& passName,
                    bool inputs);
  void checkSlotName(const std::string& slot, const std::string& pointer, bool inInputs, PassInfo& info,
                     const std::string& passName);
  void checkSlots(const PassInfo& info, PassDecl& decl);
  void checkParams(const Json& values, const std::string& pointer, const PassInfo& info, const std::string& passName,
                   ParamSet& params);
  std::optional<ParamValue> checkParam(const ParamDecl& decl, const Json& v, const std::string& pointer,
                                       const PassInfo& info, const std::string& passName);

  // config_build_samplers.cpp: the pass key "samplers" (config_.samplers)
  void checkSamplerOverrides(const Json& samplers, const std::string& pointer, const PassInfo& info,
                             const std::string& passName);
  void readSamplerState(const Json& object, const std::string& pointer, const PassInfo& info,
                        const std::string& passName, SamplerState& s);
  void readSamplerWrap(const Json& v, const std::string& pointer, const std::string& passName, SamplerState& s);
  bool readSamplerBorder(const Json& v, const std::string& pointer, const std::string& passName, SamplerState& s);
  template <class E, class Parse>
  bool samplerChoice(const Json& v, const std::string& pointer, const std::string& what,
                     const std::vector<std::string>& names, Parse parse, E& out, const std::string& passName);

  const ConfigDocument& doc_;
  const Json& root_;
  const config_detail::SourceMap& map_;
  const PassRegistry& registry_;
  Diagnostics& diags_;
  PipelineConfig config_;
  std::vector<PassInfo> passInfo_;  // parallel to config_.graph.passes
  std::vector<bool> formatOk_;      // parallel to config_.graph.resources
};

}  // namespace rgraph::config_detail
