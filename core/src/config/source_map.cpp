// A minimal JSON position scanner (see source_map.h for why it exists).
// It runs on text nlohmann-json has already accepted, so it does not validate:
// it only has to find where values and keys start. It is iterative (an
// explicit stack), so deep nesting cannot overflow the C++ stack.
#include "source_map.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <unordered_set>

namespace rgraph::config_detail {

std::string escapePointerToken(std::string_view token) {
  std::string out;
  out.reserve(token.size());
  for (char c : token) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::string parentPointer(const std::string& pointer) {
  size_t slash = pointer.rfind('/');
  return slash == std::string::npos ? std::string() : pointer.substr(0, slash);
}

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Decodes the string literal text[begin, end) (quotes included) to UTF-8.
// Literals without a backslash are copied; the rare escaped key is handed to
// the JSON library, which already accepted it.
std::string decodeString(std::string_view literal) {
  if (literal.find('\\') == std::string_view::npos) return std::string(literal.substr(1, literal.size() - 2));
  try {
    return nlohmann::json::parse(literal).get<std::string>();
  } catch (const std::exception&) {
    return std::string(literal.substr(1, literal.size() - 2));
  }
}

}  // namespace

void SourceMap::indexLines(std::string_view text) {
  lineStarts_.assign(1, 0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') lineStarts_.push_back(i + 1);
}

bool SourceMap::scan(std::string_view text, size_t* tooDeepAt) {
  indexLines(text);
  values_.clear();
  keys_.clear();
  duplicates_.clear();
  duplicateOffsets_.clear();

  const size_t n = text.size();
  size_t pos = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // UTF-8 byte order mark
  auto skipSpace = [&] {
    while (pos < n && isSpace(text[pos])) ++pos;
  };
  // Moves pos past the string literal starting at pos (an opening quote).
  auto skipString = [&] {
    ++pos;
    while (pos < n && text[pos] != '"') pos += text[pos] == '\\' ? 2 : 1;
    pos = std::min(pos + 1, n);
  };

  // One open container: is it an object, how many members/elements so far,
  // and the pointer length to restore before the next member.
  struct Frame {
    bool object;
    size_t count;
    size_t pointerLength;
    std::unordered_set<std::string> keys;  // to spot a key repeated in this object
  };
  std::vector<Frame> stack;
  std::string pointer;  // pointer of the value about to be scanned

  // Positions pos at the next member/element of the innermost container and
  // extends `pointer` with its token. Returns false on unexpected text.
  auto enterMember = [&]() -> bool {
    Frame& frame = stack.back();
    pointer.resize(frame.pointerLength);
    skipSpace();
    if (!frame.object) {
      pointer += "/" + std::to_string(frame.count);
      return true;
    }
    if (pos >= n || text[pos] != '"') return false;
    size_t keyStart = pos;
    skipString();
    std::string key = decodeString(text.substr(keyStart, pos - keyStart));
    pointer += "/" + escapePointerToken(key);
    // Duplicate keys: the JSON library keeps the last value, so do we.
    keys_.insert_or_assign(pointer, keyStart);
    if (!frame.keys.insert(std::move(key)).second) {
      duplicates_.push_back(pointer);
      duplicateOffsets_.push_back(keyStart);
    }
    skipSpace();
    if (pos >= n || text[pos] != ':') return false;
    ++pos;
    return true;
  };

  for (;;) {
    // A value starts here.
    skipSpace();
    if (pos >= n) return true;
    values_.insert_or_assign(pointer, pos);
    char c = text[pos];
    if (c == '{' || c == '[') {
      if (stack.size() >= kMaxDepth) {
        if (tooDeepAt) *tooDeepAt = pos;
        return false;
      }
      stack.push_back({c == '{', 0, pointer.size(), {}});
      ++pos;
      skipSpace();
      if (pos < n && (text[pos] == '}' || text[pos] == ']')) {
        ++pos;
        stack.pop_back();
      } else {
        if (!enterMember()) return true;
        continue;
      }
    } else if (c == '"') {
      skipString();
    } else {
      // number or literal: runs until a delimiter
      while (pos < n && !isSpace(text[pos]) && text[pos] != ',' && text[pos] != ']' && text[pos] != '}') ++pos;
    }

    // After a value: close containers until a ',' opens the next member.
    bool next = false;
    while (!stack.empty()) {
      skipSpace();
      if (pos >= n) return true;
      if (text[pos] == ',') {
        ++pos;
        ++stack.back().count;
        if (!enterMember()) return true;
        next = true;
        break;
      }
      // '}' or ']'
      ++pos;
      pointer.resize(stack.back().pointerLength);
      stack.pop_back();
    }
    if (!next) return true;  // the top-level value is complete
  }
}

LineColumn SourceMap::position(size_t offset) const {
  if (lineStarts_.empty()) return {1, static_cast<int>(offset) + 1};
  auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  size_t line = static_cast<size_t>(it - lineStarts_.begin());  // >= 1: lineStarts_[0] == 0
  return {static_cast<int>(line), static_cast<int>(offset - lineStarts_[line - 1]) + 1};
}

size_t SourceMap::valueOffset(const std::string& pointer) const {
  auto it = values_.find(pointer);
  return it == values_.end() ? npos : it->second;
}

size_t SourceMap::keyOffset(const std::string& pointer) const {
  auto it = keys_.find(pointer);
  return it == keys_.end() ? npos : it->second;
}

}  // namespace rgraph::config_detail
