// Internal to the config loader: where each JSON value sits in the text.
//
// nlohmann-json 3.11 does not record value positions, so after the library
// has accepted the text, a small scanner walks it once more and records the
// byte offset of the first character of every value (and of every object
// key), keyed by JSON pointer. It only needs to be correct on text the
// library already validated; on anything else it stops early and the
// affected pointers fall back to their parents.
#pragma once

#include <cstddef>
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
  // Values nested deeper than this stop the scan; build() reports it.
  static constexpr size_t kMaxDepth = 256;

  // Scans `text` (already validated JSON). Returns false when the nesting
  // exceeds kMaxDepth; *tooDeepAt then holds the offset of the offending bracket.
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
  std::vector<size_t> lineStarts_;  // offset of the first byte of each line
  std::unordered_map<std::string, size_t> values_;
  std::unordered_map<std::string, size_t> keys_;
  std::vector<std::string> duplicates_;
  std::vector<size_t> duplicateOffsets_;
};

// "a/b~c" -> "a~1b~0c" (RFC 6901).
std::string escapePointerToken(std::string_view token);
// The parent of a pointer ("/a/b" -> "/a", "/a" -> ""); "" stays "".
std::string parentPointer(const std::string& pointer);

}  // namespace rgraph::config_detail
