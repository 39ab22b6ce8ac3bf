// JSON text handling shared by configs, scene files and glTF (see json_text.h).
#include "json_text.h"

#include <algorithm>

#include "ordered_dom_builder.h"

namespace rgraph::config_detail {

namespace {

using Json = nlohmann::ordered_json;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Offset of the closing quote of the string literal opening at `open` (or the
// text's size when it is unterminated).
size_t stringEnd(std::string_view text, size_t open) {
  size_t i = open + 1;
  while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
  return std::min(i, text.size());
}

// A DOM builder (linear in the object sizes, see ordered_dom_builder.h)
// whose parse error records where and why instead of throwing (number
// overflow, for instance, would otherwise arrive as an out_of_range exception
// without a position).
class DomBuilder : public OrderedDomBuilder {
 public:
  explicit DomBuilder(Json& root) : OrderedDomBuilder(root) {}

  // sax_parse calls it on the static type.
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& lastToken, const Exception& ex) {
    failed = true;
    message = ex.what();
    errorOffset = position - std::min(position, tokenLength(message, lastToken));
    return false;
  }

  bool failed = false;
  std::size_t errorOffset = 0;  // of the first byte of the offending token
  std::string message;

 private:
  // The position the library reports is just past the last character read.
  // For an unexpected number, string or literal, point at its first
  // character instead of its last. The token text is only reliable for
  // strings and numbers (the lexer resets it for those); literals have fixed
  // lengths; anything else is one character or a lexer error at that spot.
  static std::size_t tokenLength(const std::string& message, const std::string& token) {
    if (message.find("unexpected number literal") != std::string::npos ||
        message.find("unexpected string literal") != std::string::npos ||
        message.find("number overflow") != std::string::npos)
      return std::max<std::size_t>(1, token.size());
    if (message.find("unexpected true literal") != std::string::npos) return 4;
    if (message.find("unexpected false literal") != std::string::npos) return 5;
    if (message.find("unexpected null literal") != std::string::npos) return 4;
    return 1;
  }
};

// "[json.exception.parse_error.101] parse error at line 1, column 5: syntax
// error while parsing ..." -> "syntax error while parsing ...": callers print
// the position themselves.
std::string parserMessage(std::string m) {
  if (!m.empty() && m[0] == '[') {
    size_t end = m.find("] ");
    if (end != std::string::npos) m.erase(0, end + 2);
  }
  if (m.rfind("parse error", 0) == 0) {
    size_t colon = m.find(": ");
    if (colon != std::string::npos) m.erase(0, colon + 2);
  }
  // "; last read: '<token>'" repeats raw input (possibly invalid UTF-8, and
  // not always only the bad token): the position says where it is.
  size_t last = m.find("; last read: '");
  if (last != std::string::npos) {
    size_t expected = m.find("'; expected ", last);
    m.erase(last, expected == std::string::npos ? std::string::npos : expected + 1 - last);
  }
  return m;
}

// The parse itself, for text whose nesting is already bounded.
std::optional<JsonSyntaxError> parseBounded(const std::string& text, nlohmann::ordered_json& root) {
  DomBuilder builder(root);
  bool parsed = false;
  try {
    parsed = Json::sax_parse(text, &builder);
  } catch (const std::exception& e) {  // not expected: the builder does not throw
    builder.failed = true;
    builder.message = e.what();
  }
  if (!parsed || builder.failed) {
    root = Json();
    return JsonSyntaxError{std::min(builder.errorOffset, text.size()),
                           builder.message.empty() ? "invalid JSON" : parserMessage(builder.message)};
  }
  if (size_t nul = text.find('\0'); nul != std::string::npos) {
    root = Json();
    return JsonSyntaxError{nul, "unexpected NUL byte after the top-level value"};
  }
  return std::nullopt;
}

}  // namespace

std::optional<JsonSyntaxError> parseJsonText(const std::string& text, nlohmann::ordered_json& root,
                                             size_t maxDepth) {
  // Nesting is bounded before the document is built: an object member added
  // after a deep one makes its member vector grow, which copies the deep value
  // recursively (std::pair<const std::string, Json> is copied, not moved), so
  // 100,000 nested arrays followed by another key overflow the stack. Past the
  // bound only the prefix before it is parsed, so that a syntax error earlier
  // in the text is still the one reported.
  if (size_t deep = findNestingTooDeep(text, maxDepth); deep != SourceMap::npos) {
    nlohmann::ordered_json prefix;
    std::optional<JsonSyntaxError> error = parseBounded(text.substr(0, deep), prefix);
    root = nlohmann::ordered_json();
    // The prefix always ends early; an error before its end is a real one.
    if (error && error->offset + 1 < deep) return error;
    return JsonSyntaxError{deep, nestingTooDeepMessage()};
  }
  return parseBounded(text, root);
}

size_t findNestingTooDeep(std::string_view text, size_t maxDepth) {
  size_t depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      i = stringEnd(text, i);
    } else if (c == '{' || c == '[') {
      if (++depth > maxDepth) return i;
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return SourceMap::npos;
}

std::string nestingTooDeepMessage() {
  return "values nested deeper than " + std::to_string(SourceMap::kMaxDepth) + " levels are not supported";
}

size_t findTopLevelArrayElement(std::string_view text, std::string_view key, size_t index) {
  size_t depth = 0;
  std::string_view lastString;  // the last string literal at depth 1: the key when ':' follows
  bool keyMatches = false;      // the current top-level member is `key`
  bool inArray = false;         // inside that member's array (depth 2)
  bool elementNext = false;     // the next non-space byte starts an element (or closes the array)
  size_t element = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (isSpace(c)) continue;
    if (elementNext) {
      elementNext = false;
      if (c != ']' && element == index) return i;
    }
    if (c == '"') {
      const size_t end = stringEnd(text, i);
      if (depth == 1) lastString = text.substr(i + 1, end - i - 1);
      i = end;
    } else if (c == ':' && depth == 1) {
      keyMatches = lastString == key;
    } else if (c == '{' || c == '[') {
      if (depth == 1 && c == '[' && keyMatches) {
        inArray = true;
        elementNext = true;
        element = 0;
      }
      ++depth;
    } else if (c == '}' || c == ']') {
      if (depth > 0) --depth;
      if (depth <= 1) inArray = false;
    } else if (c == ',') {
      if (depth == 1) keyMatches = false;
      if (depth == 2 && inArray) {
        ++element;
        elementNext = true;
      }
    }
  }
  return SourceMap::npos;
}

SourceMap& JsonLocator::map() {
  if (!scanned_) {
    if (!map_) map_ = std::make_unique<SourceMap>();
    map_->scan(text_);  // nesting was bounded before parsing; a deeper part just stays unmapped
    scanned_ = true;
  }
  return *map_;
}

std::optional<LineColumn> JsonLocator::value(const std::string& pointer) {
  const SourceMap& m = map();
  std::string p = pointer;
  for (;;) {
    if (size_t offset = m.valueOffset(p); offset != SourceMap::npos) return m.position(offset);
    if (p.empty()) return std::nullopt;
    p = parentPointer(p);
  }
}

std::optional<LineColumn> JsonLocator::key(const std::string& pointer) {
  const SourceMap& m = map();
  if (size_t offset = m.keyOffset(pointer); offset != SourceMap::npos) return m.position(offset);
  return value(pointer);
}

LineColumn JsonLocator::position(size_t offset) {
  if (!map_) {
    map_ = std::make_unique<SourceMap>();
    map_->indexLines(text_);  // lines only: a full scan is not needed for an offset
  }
  return map_->position(offset);
}

}  // namespace rgraph::config_detail
