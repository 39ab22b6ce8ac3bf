#include "rgraph/registry.h"

#include <algorithm>
#include <exception>
#include <set>

namespace rgraph {

const SlotDecl* PassTypeDesc::findSlot(std::string_view slot) const {
  for (const auto& s : slots)
    if (s.name == slot) return &s;
  return nullptr;
}

const ParamDecl* PassTypeDesc::findParam(std::string_view param) const {
  for (const auto& p : params)
    if (p.name == param) return &p;
  return nullptr;
}

ShaderProgramSpec programSpec(std::string vert, std::string frag, std::vector<std::string> defines,
                              std::vector<SamplerSlot> samplers) {
  ShaderProgramSpec s;
  s.vert = std::move(vert);
  s.frag = std::move(frag);
  s.defines = std::move(defines);
  s.samplers = std::move(samplers);
  return s;
}

std::vector<std::string> PassTypeDesc::shaderFiles() const {
  std::vector<std::string> files;
  if (!programs) return files;
  std::vector<ShaderProgramSpec> specs;
  try {
    specs = programs(defaultParams(params));
  } catch (const std::exception&) {
    return files;  // e.g. a shader parameter without a default
  }
  for (const auto& s : specs)
    for (const std::string* f : {&s.vert, &s.frag, &s.comp})
      if (!f->empty() && std::find(files.begin(), files.end(), *f) == files.end()) files.push_back(*f);
  return files;
}

namespace {
bool fail(std::string* error, std::string msg) {
  if (error) *error = std::move(msg);
  return false;
}

bool defaultInRange(const ParamDecl& p) {
  auto inRange = [&](double v) { return (!p.min || v >= *p.min) && (!p.max || v <= *p.max); };
  if (auto* d = std::get_if<double>(&p.defaultValue)) return inRange(*d);
  if (auto* i = std::get_if<int64_t>(&p.defaultValue)) return inRange(static_cast<double>(*i));
  if (auto* v = std::get_if<std::vector<double>>(&p.defaultValue))
    return std::all_of(v->begin(), v->end(), inRange);
  return true;
}
}  // namespace

bool PassRegistry::add(PassTypeDesc desc, std::string* error) {
  if (desc.name.empty()) return fail(error, "pass type has an empty name");
  if (types_.count(desc.name)) {
    const auto& existing = types_.find(desc.name)->second;
    return fail(error, "pass type '" + desc.name + "' is already registered (from " + existing.origin + ")");
  }
  std::set<std::string> seen;
  for (const auto& s : desc.slots)
    if (!seen.insert(s.name).second)
      return fail(error, "pass type '" + desc.name + "' declares slot '" + s.name + "' twice");
  seen.clear();
  for (const auto& p : desc.params) {
    if (!seen.insert(p.name).second)
      return fail(error, "pass type '" + desc.name + "' declares parameter '" + p.name + "' twice");
    if (!defaultInRange(p))
      return fail(error, "pass type '" + desc.name + "': default of parameter '" + p.name + "' is out of its range");
  }
  for (const auto& r : desc.rules)
    if (r.text.empty() || !r.check)
      return fail(error, "pass type '" + desc.name + "' has a rule without " + (r.text.empty() ? "a sentence" : "a check"));
  if (!desc.create) return fail(error, "pass type '" + desc.name + "' has no factory");
  std::string name = desc.name;
  types_.emplace(std::move(name), std::move(desc));
  return true;
}

const PassTypeDesc* PassRegistry::find(std::string_view name) const {
  auto it = types_.find(name);
  return it == types_.end() ? nullptr : &it->second;
}

std::vector<const PassTypeDesc*> PassRegistry::all() const {
  std::vector<const PassTypeDesc*> out;
  for (const auto& [name, desc] : types_) out.push_back(&desc);
  return out;
}

std::string PassRegistry::suggest(std::string_view name) const {
  std::vector<std::string> names;
  for (const auto& [n, d] : types_) names.push_back(n);
  return closestMatch(name, names);
}

PassRegistry& PassRegistry::mutableBuiltins() {
  static PassRegistry registry;
  return registry;
}

const PassRegistry& PassRegistry::builtins() { return mutableBuiltins(); }

std::vector<std::string>& PassRegistry::builtinErrors() {
  static std::vector<std::string> errors;
  return errors;
}

PassRegistrar::PassRegistrar(PassTypeDesc (*make)()) {
  std::string error;
  if (!PassRegistry::mutableBuiltins().add(make(), &error)) PassRegistry::builtinErrors().push_back(error);
}

}  // namespace rgraph
