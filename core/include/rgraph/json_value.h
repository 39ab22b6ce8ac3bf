// JSON that a user gives outside a file (a viewer script's `param` value, a
// panel's edit), parsed with the same limits and messages as config files:
// the nesting bound (deeper values are refused before anything is built: a
// deep value copied recursively overflows the stack), number overflow (1e999)
// and syntax errors come back as an error with an offset, never as an exception.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace rgraph {

struct JsonValueError {
  size_t offset = 0;    // of the first byte of the offending token in the text
  std::string message;  // the parser's words, e.g. "number overflow parsing '1e999'"
};

// Parses `text` into `value`. `enclosingDepth`: how many levels the value
// will sit under once put into a document (a pass parameter: 4), counted
// against the nesting bound config files have, so the document stays loadable.
std::optional<JsonValueError> parseJsonValue(const std::string& text, nlohmann::ordered_json& value,
                                             size_t enclosingDepth = 0);

}  // namespace rgraph
