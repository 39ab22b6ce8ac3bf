// Pass parameter values (ParamSet): with the graph's small utilities, since
// the config loader, the pass checks and the passes all read them (no
// registry involved).
#include "rgraph/params.h"

namespace rgraph {

std::string_view paramTypeName(ParamType t) {
  switch (t) {
    case ParamType::boolean: return "bool";
    case ParamType::integer: return "int";
    case ParamType::number: return "float";
    case ParamType::string: return "string";
    case ParamType::enumeration: return "enum";
    case ParamType::vec3: return "vec3";
    case ParamType::vec4: return "vec4";
    case ParamType::shader: return "shader";
  }
  return "unknown";
}

const ParamValue* ParamSet::find(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? nullptr : &it->second;
}

bool ParamSet::getBool(const std::string& name, bool fallback) const {
  const ParamValue* v = find(name);
  if (v && std::holds_alternative<bool>(*v)) return std::get<bool>(*v);
  return fallback;
}

int64_t ParamSet::getInt(const std::string& name, int64_t fallback) const {
  const ParamValue* v = find(name);
  if (v && std::holds_alternative<int64_t>(*v)) return std::get<int64_t>(*v);
  return fallback;
}

double ParamSet::getNumber(const std::string& name, double fallback) const {
  const ParamValue* v = find(name);
  if (!v) return fallback;
  if (std::holds_alternative<double>(*v)) return std::get<double>(*v);
  if (std::holds_alternative<int64_t>(*v)) return static_cast<double>(std::get<int64_t>(*v));
  return fallback;
}

std::string ParamSet::getString(const std::string& name, const std::string& fallback) const {
  const ParamValue* v = find(name);
  if (v && std::holds_alternative<std::string>(*v)) return std::get<std::string>(*v);
  return fallback;
}

std::vector<double> ParamSet::getVector(const std::string& name, std::vector<double> fallback) const {
  const ParamValue* v = find(name);
  if (v && std::holds_alternative<std::vector<double>>(*v)) return std::get<std::vector<double>>(*v);
  return fallback;
}

ParamSet defaultParams(const std::vector<ParamDecl>& decls) {
  ParamSet set;
  for (const auto& d : decls) set.set(d.name, d.defaultValue);
  return set;
}

}  // namespace rgraph
