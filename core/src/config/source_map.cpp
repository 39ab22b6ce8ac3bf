// A minimal JSON position scanner (see source_map.h for why it exists).
// It runs on text nlohmann-json has already accepted, so it does not validate:
// it only has to find where values and keys start. It is iterative (an
// explicit stack), so deep nesting cannot overflow the C++ stack, and it
// builds no string per value: a config with a million passes maps in linear
// time.
#include "source_map.h"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

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

std::string_view SourceMap::keyOf(const Node& member) const {
  if (member.key == npos) return {};
  const size_t open = member.key;
  size_t i = open + 1;
  while (i < text_.size() && text_[i] != '"') {
    if (text_[i] == '\\') {
      auto it = escapedKeys_.find(open);
      return it == escapedKeys_.end() ? std::string_view() : it->second;
    }
    ++i;
  }
  return std::string_view(text_).substr(open + 1, i - open - 1);
}

void SourceMap::close(uint32_t node, size_t from, std::vector<uint32_t>& repeated) {
  Node& n = nodes_[node];
  n.first = static_cast<uint32_t>(children_.size());
  n.count = static_cast<uint32_t>(pending_.size() - from);
  children_.insert(children_.end(), pending_.begin() + static_cast<std::ptrdiff_t>(from), pending_.end());
  pending_.resize(from);
  if (!n.object) return;
  const uint32_t* members = children_.data() + n.first;
  if (n.count > kIndexedMembers) {
    auto& index = index_[node];
    index.reserve(n.count);
    for (uint32_t i = 0; i < n.count; ++i) {
      auto [it, inserted] = index.try_emplace(keyOf(nodes_[members[i]]), members[i]);
      if (inserted) continue;
      it->second = members[i];  // the last one counts, as in the JSON library
      repeated.push_back(members[i]);
    }
    return;
  }
  // A handful of members: comparing them pairwise is cheaper than hashing.
  for (uint32_t i = 1; i < n.count; ++i) {
    const std::string_view key = keyOf(nodes_[members[i]]);
    for (uint32_t j = 0; j < i; ++j) {
      if (keyOf(nodes_[members[j]]) != key) continue;
      repeated.push_back(members[i]);
      break;
    }
  }
}

std::string SourceMap::pointerOf(const std::vector<Frame>& stack) const {
  std::string p;
  for (size_t i = 1; i < stack.size(); ++i) {
    if (nodes_[stack[i - 1].node].object)
      p += "/" + escapePointerToken(keyOf(nodes_[stack[i].node]));
    else
      p += "/" + std::to_string(stack[i].slot - stack[i - 1].from);
  }
  return p;
}

void SourceMap::closeInnermost(std::vector<Frame>& stack) {
  std::vector<uint32_t> repeated;
  close(stack.back().node, stack.back().from, repeated);
  if (!repeated.empty()) {  // rare: the pointer is built only for its message
    const std::string p = pointerOf(stack);
    for (uint32_t m : repeated) {
      duplicates_.push_back(p + "/" + escapePointerToken(keyOf(nodes_[m])));
      duplicateOffsets_.push_back(nodes_[m].key);
    }
  }
  stack.pop_back();
}

bool SourceMap::scan(std::string_view text, size_t* tooDeepAt) {
  text_.assign(text);
  indexLines(text_);
  nodes_.clear();
  children_.clear();
  pending_.clear();
  index_.clear();
  keyPool_.clear();
  escapedKeys_.clear();
  duplicates_.clear();
  duplicateOffsets_.clear();

  const std::string_view t = text_;
  const size_t n = t.size();
  size_t pos = 0;
  if (t.substr(0, 3) == "\xEF\xBB\xBF") pos = 3;  // UTF-8 byte order mark
  auto skipSpace = [&] {
    while (pos < n && isSpace(t[pos])) ++pos;
  };
  // Moves pos past the string literal starting at pos (an opening quote).
  auto skipString = [&] {
    ++pos;
    while (pos < n && t[pos] != '"') pos += t[pos] == '\\' ? 2 : 1;
    pos = std::min(pos + 1, n);
  };

  std::vector<Frame> stack;
  size_t nextKey = npos;  // key offset of the member whose value comes next
  auto closeTop = [&] { closeInnermost(stack); };
  // Text the scanner cannot follow ends the scan: what was read stays mapped.
  auto finish = [&] {
    while (!stack.empty()) closeTop();
  };

  // Positions pos at the next member/element of the innermost container and
  // notes its key. Returns false on unexpected text.
  auto enterMember = [&]() -> bool {
    skipSpace();
    if (!nodes_[stack.back().node].object) return true;
    if (pos >= n || t[pos] != '"') return false;
    const size_t keyStart = pos;
    skipString();
    const std::string_view literal = t.substr(keyStart, pos - keyStart);
    if (literal.find('\\') != std::string_view::npos) {
      keyPool_.push_back(decodeString(literal));
      escapedKeys_[keyStart] = keyPool_.back();
    }
    nextKey = keyStart;
    skipSpace();
    if (pos >= n || t[pos] != ':') return false;
    ++pos;
    return true;
  };

  for (;;) {
    // A value starts here.
    skipSpace();
    if (pos >= n || nodes_.size() >= std::numeric_limits<uint32_t>::max()) {
      finish();
      return true;
    }
    const uint32_t id = static_cast<uint32_t>(nodes_.size());
    const size_t slot = stack.empty() ? npos : pending_.size();
    nodes_.push_back(Node{pos, nextKey, 0, 0, false});
    nextKey = npos;
    if (!stack.empty()) pending_.push_back(id);
    const char c = t[pos];
    if (c == '{' || c == '[') {
      if (stack.size() >= kMaxDepth) {
        if (tooDeepAt) *tooDeepAt = pos;
        finish();
        return false;
      }
      nodes_[id].object = c == '{';
      stack.push_back({id, pending_.size(), slot});
      ++pos;
      skipSpace();
      if (pos < n && (t[pos] == '}' || t[pos] == ']')) {
        ++pos;
        closeTop();
      } else {
        if (!enterMember()) {
          finish();
          return true;
        }
        continue;
      }
    } else if (c == '"') {
      skipString();
    } else {
      // number or literal: runs until a delimiter
      while (pos < n && !isSpace(t[pos]) && t[pos] != ',' && t[pos] != ']' && t[pos] != '}') ++pos;
    }

    // After a value: close containers until a ',' opens the next member.
    bool next = false;
    while (!stack.empty()) {
      skipSpace();
      if (pos >= n) {
        finish();
        return true;
      }
      if (t[pos] == ',') {
        ++pos;
        if (!enterMember()) {
          finish();
          return true;
        }
        next = true;
        break;
      }
      // '}' or ']'
      ++pos;
      closeTop();
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

size_t SourceMap::member(uint32_t node, std::string_view key) const {
  const Node& object = nodes_[node];
  if (object.count > kIndexedMembers) {
    auto index = index_.find(node);
    if (index == index_.end()) return npos;
    auto it = index->second.find(key);
    return it == index->second.end() ? npos : it->second;
  }
  for (uint32_t i = object.count; i-- > 0;) {  // from the end: the last of a repeated key
    const uint32_t m = children_[object.first + i];
    if (keyOf(nodes_[m]) == key) return m;
  }
  return npos;
}

size_t SourceMap::find(const std::string& pointer) const {
  if (nodes_.empty()) return npos;
  size_t node = 0;
  std::string token;
  for (size_t pos = 0; pos < pointer.size();) {
    if (pointer[pos] != '/') return npos;
    size_t end = pointer.find('/', pos + 1);
    if (end == std::string::npos) end = pointer.size();
    token.clear();
    for (size_t i = pos + 1; i < end; ++i) {  // undo the escapes ~1 and ~0
      if (pointer[i] == '~' && i + 1 < end && (pointer[i + 1] == '0' || pointer[i + 1] == '1'))
        token += pointer[++i] == '1' ? '/' : '~';
      else
        token += pointer[i];
    }
    pos = end;
    const Node& n = nodes_[node];
    if (n.count == 0) return npos;  // a scalar or an empty container
    if (n.object) {
      node = member(static_cast<uint32_t>(node), token);
      if (node == npos) return npos;
      continue;
    }
    // An array index: digits without a leading zero, as pointers write them.
    if (token.empty() || token.size() > 10 || (token.size() > 1 && token[0] == '0') ||
        !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return npos;
    const uint64_t index = std::stoull(token);
    if (index >= n.count) return npos;
    node = children_[n.first + index];
  }
  return node;
}

size_t SourceMap::valueOffset(const std::string& pointer) const {
  const size_t node = find(pointer);
  return node == npos ? npos : nodes_[node].value;
}

size_t SourceMap::keyOffset(const std::string& pointer) const {
  const size_t node = find(pointer);
  return node == npos ? npos : nodes_[node].key;
}

}  // namespace rgraph::config_detail
