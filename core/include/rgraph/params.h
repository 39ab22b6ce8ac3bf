// Typed pass parameters: declarations (in a pass type) and values (in a config).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace rgraph {

// `shader`: a shader file name (a string), relative to the shader folders; the
// config loader refuses absolute names and names that lead outside them.
enum class ParamType { boolean, integer, number, string, enumeration, vec3, vec4, shader };
std::string_view paramTypeName(ParamType t);

// bool, integer, number, string/enumeration/shader, vec3/vec4
using ParamValue = std::variant<bool, int64_t, double, std::string, std::vector<double>>;

struct ParamDecl {
  std::string name;
  ParamType type = ParamType::number;
  ParamValue defaultValue;
  std::optional<double> min, max;       // integer/number (and each vector component)
  std::vector<std::string> choices;     // enumeration
  std::string description;              // one line
};

// Values of one pass instance, defaults filled in by the config loader.
class ParamSet {
 public:
  void set(const std::string& name, ParamValue v) { values_[name] = std::move(v); }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const ParamValue* find(const std::string& name) const;

  // Typed getters return `fallback` when absent or of another type.
  bool getBool(const std::string& name, bool fallback = false) const;
  int64_t getInt(const std::string& name, int64_t fallback = 0) const;
  double getNumber(const std::string& name, double fallback = 0.0) const;  // integers convert
  std::string getString(const std::string& name, const std::string& fallback = {}) const;
  std::vector<double> getVector(const std::string& name, std::vector<double> fallback = {}) const;

  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  std::map<std::string, ParamValue> values_;
};

// A ParamSet holding every declared default.
ParamSet defaultParams(const std::vector<ParamDecl>& decls);

}  // namespace rgraph
