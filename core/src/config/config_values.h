// Internal to the config loader: single JSON values to typed values, and how
// messages show them. Integers are read exactly (2^64-1 stays 2^64-1, never
// 1.84467e+19), and every limit a value breaks is named in the message. The
// document's structure (keys, resources, passes, bindings) is checked in
// config_build*.cpp; this file knows only values and their declarations.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config_impl.h"
#include "rgraph/diagnostics.h"
#include "rgraph/params.h"

namespace rgraph::config_detail {

std::string jsonTypeName(const Json& v);
// 12, 0.5, 1e+300; whole numbers below 1e15 without a fraction.
std::string formatNumber(double v);
// A short rendering of a value for messages: numbers as written where that is
// exact (18446744073709551615, -0), 2.5, 'text', true, array...
std::string describeValue(const Json& v);
std::string quotedList(const std::vector<std::string>& items);
// " (did you mean 'x'?)" or "".
std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates);

// An integer read from JSON: 4 and 4.0 are integers, 4.5 is not; -0 is 0.
struct IntegerValue {
  enum class Status { ok, not_a_number, not_integral, too_large, too_small } status = Status::ok;
  int64_t value = 0;
};
IntegerValue readInteger(const Json& v);

// An integer from min to max. Returns "" and sets `out` when `v` is one,
// otherwise what is wrong, starting with `what` ("buffer_bytes 1e+300 is too
// large: at most ..."). `unit` follows the upper limit ("bytes"); `hint` ends
// range messages (e.g. " (0: a full chain)").
std::string integerInRange(const Json& v, const std::string& what, int64_t min, int64_t max, int64_t& out,
                           const std::string& unit = {}, const std::string& hint = {});

// A number that a float (as passes and GL use them) holds: "" or what is wrong.
std::string floatProblem(double x);

// A problem with a parameter value: the message lacks the "parameter 'p' of
// pass 'x': " prefix, which the caller adds.
struct ValueProblem {
  DiagCode code = DiagCode::param_type;
  std::string pointer;  // the value, or one vector component
  std::string message;
};
// A parameter value checked against its declaration (type, range, choices,
// and for shader files: a name inside the shader folders).
std::optional<ParamValue> checkParamValue(const ParamDecl& decl, const Json& v, const std::string& pointer,
                                          std::vector<ValueProblem>& problems);

}  // namespace rgraph::config_detail
