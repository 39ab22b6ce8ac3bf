// rgraph passes [TYPE...] [--plugin NAME] [--json]: what a config may name in
// "type", and for each type what it binds under "inputs" and "outputs" (slot,
// access, accepted formats), the "params" it takes (type, default, range or
// choices) and the rules its checks enforce. Everything printed is read from
// the registered PassTypeDesc; nothing here knows a pass type.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"

namespace rgraph::cli {
namespace {

std::string_view loadName(SlotDecl::Load l) {
  switch (l) {
    case SlotDecl::Load::never: return "never";
    case SlotDecl::Load::optional: return "optional";
    case SlotDecl::Load::required: return "required";
  }
  return "never";
}

// A range bound in the parameter's own type: an int parameter's 1, not 1.0.
nlohmann::json bound(const ParamDecl& p, double v) {
  if (p.type == ParamType::integer) return static_cast<int64_t>(v);
  return v;
}

nlohmann::json paramValueJson(const ParamValue& v) {
  return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

// The sentences of what a type requires beyond slot formats: its rules, and
// what its needsScene and sideEffect flags mean for a config.
std::vector<std::string> ruleTexts(const PassTypeDesc& t) {
  std::vector<std::string> out;
  for (const auto& r : t.rules) out.push_back(r.text);
  if (t.needsScene) out.push_back("needs a scene (it draws or lights it): refused when rendering without one");
  if (t.sideEffect) out.push_back("always runs (a side effect: never culled)");
  return out;
}

// A declared sampler state under the names the config's "samplers" key takes.
nlohmann::json samplerJson(const SamplerState& st) {
  nlohmann::json wrap = nlohmann::json::array();
  for (SamplerState::Wrap w : st.wrap) wrap.push_back(wrapName(w));
  return {{"filter", filterName(st.filter)}, {"mip", mipFilterName(st.mip)}, {"wrap", wrap},
          {"border", st.border}, {"compare", compareName(st.compare)}, {"anisotropy", st.anisotropy}};
}

nlohmann::json typeJson(const PassTypeDesc& t) {
  nlohmann::json slots = nlohmann::json::array();
  for (const auto& s : t.slots) {
    nlohmann::json formats = nlohmann::json::array();
    for (Format f : s.formats) formats.push_back(formatName(f));
    slots.push_back({{"name", s.name},
                     {"access", accessName(s.access)},
                     {"binds_in", isWriteAccess(s.access) ? "outputs" : "inputs"},
                     {"required", s.required},
                     {"load", loadName(s.load)},
                     {"formats", formats},
                     {"multisampled", s.acceptsMultisample},
                     {"description", s.description},
                     {"sampler", s.sampler ? samplerJson(*s.sampler) : nlohmann::json()}});
  }
  nlohmann::json params = nlohmann::json::array();
  for (const auto& p : t.params) {
    nlohmann::json pj = {{"name", p.name},
                         {"type", paramTypeName(p.type)},
                         {"default", paramValueJson(p.defaultValue)},
                         {"description", p.description}};
    if (p.min) pj["min"] = bound(p, *p.min);
    if (p.max) pj["max"] = bound(p, *p.max);
    if (!p.choices.empty()) pj["choices"] = p.choices;
    params.push_back(pj);
  }
  return {{"type", t.name},          {"description", t.description}, {"origin", t.origin},
          {"side_effect", t.sideEffect}, {"needs_scene", t.needsScene},  {"shaders", t.shaderFiles()},
          {"slots", slots},          {"params", params},             {"rules", ruleTexts(t)}};
}

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

// What a slot accepts: its formats (or any), and multisampled images.
std::string slotAccepts(const SlotDecl& s) {
  std::vector<std::string> formats;
  for (Format f : s.formats) formats.emplace_back(formatName(f));
  std::string out = formats.empty() ? "any format" : "formats " + join(formats, ", ");
  if (s.acceptsMultisample) out += "; multisampled too";
  return out;
}

// What values a parameter takes beyond its type: choices or range.
std::string paramAccepts(const ParamDecl& p) {
  if (!p.choices.empty()) {
    std::vector<std::string> quoted;
    for (const auto& c : p.choices) quoted.push_back(nlohmann::json(c).dump());
    return "one of " + join(quoted, ", ");
  }
  std::string range;
  if (p.min && p.max)
    range = bound(p, *p.min).dump() + " to " + bound(p, *p.max).dump();
  else if (p.min)
    range = ">= " + bound(p, *p.min).dump();
  else if (p.max)
    range = "<= " + bound(p, *p.max).dump();
  if (!range.empty() && (p.type == ParamType::vec3 || p.type == ParamType::vec4)) range = "each " + range;
  return range;
}

std::string padded(const std::string& s, size_t width) { return s + std::string(width > s.size() ? width - s.size() : 0, ' '); }

// One type as text. Columns line up within the type; every name is at least
// two spaces from what follows (a long name never runs into its type).
void printType(const PassTypeDesc& t, std::ostream& out) {
  out << t.name << "  (" << t.origin << ")\n  " << t.description << "\n";
  size_t nameW = 0, accessW = 0, typeW = 0, defaultW = 0;
  for (const auto& s : t.slots) {
    nameW = std::max(nameW, s.name.size());
    accessW = std::max(accessW, accessName(s.access).size());
  }
  for (const auto& p : t.params) {
    nameW = std::max(nameW, p.name.size());
    typeW = std::max(typeW, paramTypeName(p.type).size());
    defaultW = std::max(defaultW, paramValueJson(p.defaultValue).dump().size());
  }
  nameW += 2;
  const std::string under(4 + nameW, ' ');  // descriptions start below the second column
  for (const bool writes : {false, true}) {
    bool first = true;
    for (const auto& s : t.slots) {
      if (isWriteAccess(s.access) != writes) continue;
      if (first) out << (writes ? "  outputs:\n" : "  inputs:\n");
      first = false;
      out << "    " << padded(s.name, nameW) << padded(s.required ? "required" : "optional", 10)
          << padded(std::string(accessName(s.access)), accessW + 2) << slotAccepts(s) << "\n";
      if (!s.description.empty()) out << under << s.description << "\n";
      if (s.sampler) out << under << "sampled " << describeSampler(*s.sampler) << "\n";
      if (s.load != SlotDecl::Load::never)
        out << under << (s.load == SlotDecl::Load::required ? "must" : "may")
            << " also be bound in inputs, to the version it draws over (load " << loadName(s.load) << ")\n";
    }
  }
  if (!t.params.empty()) out << "  params:\n";
  for (const auto& p : t.params) {
    const std::string accepts = paramAccepts(p);
    std::string line = "    " + padded(p.name, nameW) + padded(std::string(paramTypeName(p.type)), typeW + 2) + "= " +
                       padded(paramValueJson(p.defaultValue).dump(), accepts.empty() ? 0 : defaultW + 2) + accepts;
    out << line << "\n";
    if (!p.description.empty()) out << under << p.description << "\n";
  }
  const auto rules = ruleTexts(t);
  if (!rules.empty()) out << "  rules:\n";
  for (const auto& r : rules) out << "    " << r << "\n";
}

// The types to list: the named ones, else those of the plugins given with
// --plugin, else every registered one. nullopt (after an error) when a name
// is unknown.
std::optional<std::vector<const PassTypeDesc*>> selectTypes(const PassesOptions& o) {
  const PassRegistry& registry = cli::registry();
  std::vector<const PassTypeDesc*> out;
  if (!o.types.empty()) {
    bool ok = true;
    for (const auto& name : o.types) {
      if (const PassTypeDesc* t = registry.find(name)) {
        out.push_back(t);
        continue;
      }
      ok = false;
      std::cerr << "error: unknown pass type '" << name << "'";
      if (const std::string near = registry.suggest(name); !near.empty())
        std::cerr << " (did you mean '" << near << "'?)";
      std::cerr << "; `rgraph passes` lists every type"
                << (o.plugins.empty() ? ", `rgraph passes --plugin NAME` a plugin's" : "") << "\n";
    }
    if (!ok) return std::nullopt;
    return out;
  }
  if (o.plugins.empty()) return registry.all();
  for (const auto& plugin : pluginLoader().loaded())
    for (const auto& name : plugin.passTypes)
      if (const PassTypeDesc* t = registry.find(name); t && std::find(out.begin(), out.end(), t) == out.end())
        out.push_back(t);
  return out;
}

}  // namespace

int runPasses(const PassesOptions& o) {
  for (const auto& e : PassRegistry::builtinErrors()) std::cerr << "error: built-in pass failed to register: " << e << "\n";
  if (!loadPlugins(o.plugins)) return kExitFailure;
  const auto types = selectTypes(o);
  if (!types) return kExitFailure;
  if (o.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const PassTypeDesc* t : *types) out.push_back(typeJson(*t));
    std::cout << out.dump(2) << "\n";
  } else {
    for (size_t i = 0; i < types->size(); ++i) {
      if (i) std::cout << "\n";
      printType(*(*types)[i], std::cout);
    }
  }
  return PassRegistry::builtinErrors().empty() ? kExitOk : kExitFailure;
}

}  // namespace rgraph::cli
