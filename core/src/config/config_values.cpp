// Single JSON values to typed values for the config loader (see config_values.h).
#include "config_values.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "rgraph/diagnostics.h"  // closestMatch

namespace rgraph::config_detail {

std::string jsonTypeName(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return "bool";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
      return "int";
    case Json::value_t::number_float:
      return "float";
    case Json::value_t::string:
      return "string";
    case Json::value_t::array:
      return "array";
    case Json::value_t::object:
      return "object";
    default:
      return "value";
  }
}

std::string formatNumber(double v) {
  if (v == 0.0 && std::signbit(v)) return "-0";
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e15) {
    return std::to_string(static_cast<int64_t>(v));
  }
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::string describeValue(const Json& v) {
  // Integers exactly as the file has them: 2^64-1 must not read 1.84467e+19.
  if (v.is_number_unsigned()) return std::to_string(v.get<uint64_t>());
  if (v.is_number_integer()) return std::to_string(v.get<int64_t>());
  if (v.is_number()) return formatNumber(v.get<double>());
  if (v.is_string()) return "'" + v.get<std::string>() + "'";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  return jsonTypeName(v);
}

std::string quotedList(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", '" : "'") + items[i] + "'";
  return out;
}

std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best = closestMatch(word, candidates);
  return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

IntegerValue readInteger(const Json& v) {
  IntegerValue r;
  if (v.is_number_unsigned()) {
    uint64_t u = v.get<uint64_t>();
    if (u > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()))
      r.status = IntegerValue::Status::too_large;
    else
      r.value = static_cast<int64_t>(u);
  } else if (v.is_number_integer()) {
    r.value = v.get<int64_t>();
  } else if (v.is_number_float()) {
    double d = v.get<double>();
    // 2^63 is the first double that int64_t cannot hold.
    if (d != std::floor(d))
      r.status = IntegerValue::Status::not_integral;
    else if (d >= 9223372036854775808.0)
      r.status = IntegerValue::Status::too_large;
    else if (d < -9223372036854775808.0)
      r.status = IntegerValue::Status::too_small;
    else
      r.value = static_cast<int64_t>(d);  // -0.0 becomes 0
  } else {
    r.status = IntegerValue::Status::not_a_number;
  }
  return r;
}

std::string integerInRange(const Json& v, const std::string& what, int64_t min, int64_t max, int64_t& out,
                           const std::string& unit, const std::string& hint) {
  const IntegerValue i = readInteger(v);
  const std::string u = unit.empty() ? std::string() : " " + unit;
  const std::string got = what + " " + describeValue(v);
  switch (i.status) {
    case IntegerValue::Status::not_a_number:
      return what + " must be an integer, got " + jsonTypeName(v);
    case IntegerValue::Status::not_integral:
      return what + " must be a whole number, got " + describeValue(v);
    case IntegerValue::Status::too_large:
      return got + " is too large: at most " + std::to_string(max) + u + hint;
    case IntegerValue::Status::too_small:
      return got + " is too small: at least " + std::to_string(min) + hint;
    case IntegerValue::Status::ok:
      break;
  }
  if (i.value > max) return got + " is too large: at most " + std::to_string(max) + u + hint;
  if (i.value < min) return got + " is too small: at least " + std::to_string(min) + hint;
  out = i.value;
  return {};
}

std::string floatProblem(double x) {
  if (std::fabs(x) <= static_cast<double>(FLT_MAX)) return {};
  return formatNumber(x) + " does not fit a 32-bit float (at most " + formatNumber(static_cast<double>(FLT_MAX)) +
         " in magnitude)";
}

namespace {

// A shader file name from a config: relative to the shader folders and staying
// inside them. The files themselves are looked up (and symbolic links checked)
// when the shader is loaded (findShaderFile); this catches what the text alone shows.
std::string shaderNameProblem(const std::string& s) {
  if (s.empty()) return "expected a shader file name, got an empty string";
  if (s.find('\0') != std::string::npos) return "the shader file name contains a NUL byte";
  const std::filesystem::path p(s);
  const std::string folders =
      "the shader folders (the built-in shaders, a plugin's own, folders given with --shader-path)";
  if (p.has_root_directory() || p.has_root_name())
    return "'" + s + "' is an absolute path; shader files are named relative to " + folders;
  const std::filesystem::path n = p.lexically_normal();
  if (!n.empty() && *n.begin() == "..") return "'" + s + "' leads outside " + folders + "; name a file inside them";
  return {};
}

// Only for a value beyond a bound the declaration has: a param may declare
// neither (an empty std::optional must not be read).
std::string rangeOf(const ParamDecl& decl) {
  if (decl.min && decl.max) return "outside its range [" + formatNumber(*decl.min) + ", " + formatNumber(*decl.max) + "]";
  if (decl.min) return "below its minimum " + formatNumber(*decl.min);
  if (decl.max) return "above its maximum " + formatNumber(*decl.max);
  return "outside its range";
}

}  // namespace

std::optional<ParamValue> checkParamValue(const ParamDecl& decl, const Json& v, const std::string& pointer,
                                          std::vector<ValueProblem>& problems) {
  const std::string expected(paramTypeName(decl.type));
  auto fail = [&](DiagCode code, const std::string& where, std::string message) {
    problems.push_back({code, where, std::move(message)});
    return std::nullopt;
  };
  auto wrongType = [&](const std::string& exp) {
    return fail(DiagCode::param_type, pointer, "expected " + exp + ", got " + jsonTypeName(v));
  };
  const std::string rangeText = rangeOf(decl);
  // One number against the declared range and the float range; `where` is the
  // value or vector component `component` (-1: the value itself).
  auto number = [&](const Json& x, const std::string& where, int component) {
    const double d = x.get<double>();
    const std::string c = "component " + std::to_string(component);
    if ((decl.min && d < *decl.min) || (decl.max && d > *decl.max)) {
      fail(DiagCode::param_range, where, (component < 0 ? "value " : c + " is ") + describeValue(x) + ", " + rangeText);
      return false;
    }
    if (std::string why = floatProblem(d); !why.empty()) {
      fail(DiagCode::param_range, where, (component < 0 ? "value " : c + ": ") + why);
      return false;
    }
    return true;
  };

  switch (decl.type) {
    case ParamType::boolean:
      if (!v.is_boolean()) return wrongType(expected);
      return ParamValue{v.get<bool>()};
    case ParamType::integer: {
      const IntegerValue i = readInteger(v);
      using S = IntegerValue::Status;
      if (i.status == S::not_a_number) return wrongType(expected);
      if (i.status == S::not_integral)
        return fail(DiagCode::param_type, pointer, "expected int, got " + describeValue(v));
      const std::string shown = describeValue(v);
      if ((i.status == S::too_large && decl.max) || (i.status == S::too_small && decl.min))
        return fail(DiagCode::param_range, pointer, "value " + shown + ", " + rangeText);
      if (i.status == S::too_large)
        return fail(DiagCode::param_range, pointer,
                    "value " + shown + " is too large: an int parameter is at most " +
                        std::to_string(std::numeric_limits<int64_t>::max()));
      if (i.status == S::too_small)
        return fail(DiagCode::param_range, pointer,
                    "value " + shown + " is too small: an int parameter is at least " +
                        std::to_string(std::numeric_limits<int64_t>::min()));
      const double d = static_cast<double>(i.value);
      if ((decl.min && d < *decl.min) || (decl.max && d > *decl.max))
        return fail(DiagCode::param_range, pointer, "value " + shown + ", " + rangeText);
      return ParamValue{i.value};
    }
    case ParamType::number: {
      if (!v.is_number()) return wrongType(expected);
      if (!number(v, pointer, -1)) return std::nullopt;
      return ParamValue{v.get<double>()};
    }
    case ParamType::string:
      if (!v.is_string()) return wrongType(expected);
      // Strings are built in place: GCC 12 warns (-Wfree-nonheap-object,
      // wrongly) about a temporary ParamValue holding one here.
      return std::optional<ParamValue>(std::in_place, std::in_place_type<std::string>, v.get<std::string>());
    case ParamType::shader: {
      if (!v.is_string()) return wrongType("a shader file name (string)");
      std::string s = v.get<std::string>();
      if (std::string why = shaderNameProblem(s); !why.empty()) return fail(DiagCode::param_range, pointer, why);
      return std::optional<ParamValue>(std::in_place, std::in_place_type<std::string>, std::move(s));
    }
    case ParamType::enumeration: {
      if (!v.is_string()) return wrongType("one of " + quotedList(decl.choices));
      std::string s = v.get<std::string>();
      if (std::find(decl.choices.begin(), decl.choices.end(), s) == decl.choices.end())
        return fail(DiagCode::param_range, pointer,
                    "'" + s + "' is not one of " + quotedList(decl.choices) + didYouMean(s, decl.choices));
      return ParamValue{s};
    }
    case ParamType::vec3:
    case ParamType::vec4: {
      const size_t n = decl.type == ParamType::vec3 ? 3 : 4;
      const std::string exp = expected + " (an array of " + std::to_string(n) + " numbers)";
      if (!v.is_array()) return wrongType(exp);
      if (v.size() != n)
        return fail(DiagCode::param_type, pointer, "expected " + exp + ", got an array of " + std::to_string(v.size()));
      std::vector<double> out;
      bool ok = true;
      for (size_t i = 0; i < n; ++i) {
        const std::string ep = pointer + "/" + std::to_string(i);
        if (!v[i].is_number()) {
          fail(DiagCode::param_type, ep,
               "component " + std::to_string(i) + ": expected a number, got " + jsonTypeName(v[i]));
          ok = false;
        } else if (!number(v[i], ep, static_cast<int>(i))) {
          ok = false;
        } else {
          out.push_back(v[i].get<double>());
        }
      }
      if (!ok) return std::nullopt;
      return ParamValue{std::move(out)};
    }
  }
  return std::nullopt;
}

}  // namespace rgraph::config_detail
