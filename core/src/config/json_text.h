// JSON text handling shared by the loaders that report file:line:column
// (pipeline configs, scene files, glTF): the parse with located errors, the
// nesting bound, and positions computed only when a message needs one.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "source_map.h"

namespace rgraph::config_detail {

struct JsonSyntaxError {
  size_t offset = 0;    // of the first byte of the offending token
  std::string message;  // the library's text without its "[json.exception...] parse error at ..." prefix
};

// Parses `text` into `root` with nlohmann's DOM builder, except that an error
// (syntax, number overflow such as 1e400) comes back with its offset instead
// of as an exception. A NUL byte after the value is an error too (the library
// stops there as if the input ended). Nesting deeper than
// SourceMap::kMaxDepth is an error at the bracket that opens the level too
// many, found before the document is built (building one copies deep values
// recursively); a syntax error earlier in the text is reported instead.
// `maxDepth` below the bound: a value that will be put that deep into a document (rgraph/json_value.h).
std::optional<JsonSyntaxError> parseJsonText(const std::string& text, nlohmann::ordered_json& root,
                                             size_t maxDepth = SourceMap::kMaxDepth);

// Offset of the first '{' or '[' that opens a level deeper than maxDepth, or
// SourceMap::npos. A byte walk that skips string literals and needs nothing
// else: it works on any bytes, so it can run before a parser that recurses
// (tinygltf turns extras into nested values recursively). On any prefix a
// JSON parser accepts, the count of open brackets is the parser's depth.
size_t findNestingTooDeep(std::string_view text, size_t maxDepth = SourceMap::kMaxDepth);
// "values nested deeper than 256 levels are not supported"
std::string nestingTooDeepMessage();

// Offset of element `index` of the array that is the value of the top-level
// key `key` (compared as written, without unescaping), or npos when there is
// no such element. A byte walk like findNestingTooDeep, so a loader can refuse
// an absurd array (a million lights) before parsing it, and say where.
size_t findTopLevelArrayElement(std::string_view text, std::string_view key, size_t index);

// Positions of values in a JSON text, scanned on first use: loaders that only
// need positions for messages pay nothing while the text is fine. The text
// must outlive the locator.
class JsonLocator {
 public:
  explicit JsonLocator(std::string_view text) : text_(text) {}
  // The position of the value at `pointer`, or of its nearest ancestor that
  // has one; nullopt when none has (text the scanner could not follow).
  std::optional<LineColumn> value(const std::string& pointer);
  // The position of the key of the member at `pointer` (else of its value).
  std::optional<LineColumn> key(const std::string& pointer);
  LineColumn position(size_t offset);

 private:
  SourceMap& map();
  std::string_view text_;
  std::unique_ptr<SourceMap> map_;
  bool scanned_ = false;  // map_ holds values, not only lines
};

}  // namespace rgraph::config_detail
