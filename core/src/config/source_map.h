// Internal to the config loader: where each JSON value sits in the text.
//
// nlohmann-json 3.11 does not record value positions, so after the library
// has accepted the text, a small scanner walks it once more and records the
// byte offset of the first character of every value (and of every object
// key) in a tree shaped like the document. A JSON pointer is resolved by
// walking that tree: an array element by index, an object member by key
// (hashed for large objects), so a lookup costs the pointer's length, not the
// document's size, and the map costs a few words per value (a config with a
// million resources must load in linear time and memory). The scanner only
// needs to be correct on text the library already validated; on anything
// else it stops early and the affected pointers fall back to their parents.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace rgraph::config_detail {

struct LineColumn {
  int line = 0;    // 1-based
  int column = 0;  // 1-based, in bytes (a tab counts as one)
};

class SourceMap {
 public:
  SourceMap() = default;
  // Holds views into its own copy of the text: not copyable or movable.
  SourceMap(const SourceMap&) = delete;
  SourceMap& operator=(const SourceMap&) = delete;

  // Values nested deeper than this stop the scan; build() reports it.
  static constexpr size_t kMaxDepth = 256;

  // Scans `text` (already validated JSON; the map keeps a copy to compare
  // object keys). Returns false when the nesting exceeds kMaxDepth;
  // *tooDeepAt then holds the offset of the offending bracket.
  bool scan(std::string_view text, size_t* tooDeepAt = nullptr);

  // Records where lines start (scan() does it too); enough for position().
  void indexLines(std::string_view text);
  // Byte offset -> line/column.
  LineColumn position(size_t offset) const;

  // Offset of the value / the key at this exact pointer, or npos.
  size_t valueOffset(const std::string& pointer) const;
  size_t keyOffset(const std::string& pointer) const;

  // Object members that appear more than once, as pointers to the second
  // (and later) occurrence; their key offsets are in duplicateKeyOffsets.
  const std::vector<std::string>& duplicateKeys() const { return duplicates_; }
  const std::vector<size_t>& duplicateKeyOffsets() const { return duplicateOffsets_; }

  static constexpr size_t npos = static_cast<size_t>(-1);

 private:
  // One value. Containers list their members/elements in children_[first,
  // first + count), in document order.
  struct Node {
    size_t value = npos;  // offset of the value's first character
    size_t key = npos;    // offset of the opening quote of its key (object members)
    uint32_t first = 0;
    uint32_t count = 0;
    bool object = false;
  };
  // Objects with more members than this get a hash index (see index_).
  static constexpr uint32_t kIndexedMembers = 16;

  // An open container while scanning: its node, where its children start in
  // pending_, and its own place in pending_ (its index in its parent; npos
  // for the top-level value).
  struct Frame {
    uint32_t node;
    size_t from;
    size_t slot;
  };

  // The pointer of the innermost open container.
  std::string pointerOf(const std::vector<Frame>& stack) const;
  // Closes the innermost open container; records its repeated keys.
  void closeInnermost(std::vector<Frame>& stack);
  // The decoded key of an object member (a view into text_ or keyPool_).
  std::string_view keyOf(const Node& member) const;
  // Closes the container `node` whose children are pending_[from, end):
  // moves them to children_ and indexes a large object. Members whose key
  // repeats an earlier one's are appended to `repeated`.
  void close(uint32_t node, size_t from, std::vector<uint32_t>& repeated);
  // The node at `pointer`, or npos.
  size_t find(const std::string& pointer) const;
  // The member of object `node` with this key (the last one), or npos.
  size_t member(uint32_t node, std::string_view key) const;

  std::string text_;
  std::vector<size_t> lineStarts_;  // offset of the first byte of each line
  std::vector<Node> nodes_;         // nodes_[0] is the top-level value
  std::vector<uint32_t> children_;
  std::vector<uint32_t> pending_;  // children of the containers still open
  // Large objects: node -> (key -> the member's node, the last one for a
  // repeated key, as the JSON library keeps the last value).
  std::unordered_map<uint32_t, std::unordered_map<std::string_view, uint32_t>> index_;
  std::deque<std::string> keyPool_;  // keys written with escapes, decoded (rare)
  std::unordered_map<size_t, std::string_view> escapedKeys_;  // key offset -> its decoded text in keyPool_
  std::vector<std::string> duplicates_;
  std::vector<size_t> duplicateOffsets_;
};

// "a/b~c" -> "a~1b~0c" (RFC 6901).
std::string escapePointerToken(std::string_view token);
// The parent of a pointer ("/a/b" -> "/a", "/a" -> ""); "" stays "".
std::string parentPointer(const std::string& pointer);

}  // namespace rgraph::config_detail
