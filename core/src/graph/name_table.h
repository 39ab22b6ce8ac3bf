// Name -> id lookup for the graph compiler: one open-addressing table over a
// contiguous arena of copied keys. Internal to core/src/graph (no public API).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rgraph::graph_detail {

inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

inline uint64_t hashName(std::string_view s) {
  uint64_t h = 0x9E3779B97F4A7C15ull ^ (s.size() * 0xC2B2AE3D27D4EB4Full);
  size_t i = 0;
  for (; i + 8 <= s.size(); i += 8) {
    uint64_t w;
    std::memcpy(&w, s.data() + i, 8);
    h = (h ^ w) * 0xFF51AFD7ED558CCDull;
    h ^= h >> 32;
  }
  uint64_t w = 0;
  std::memcpy(&w, s.data() + i, s.size() - i);
  h = (h ^ w) * 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 29;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 32;
  return h;
}

// Name -> id. Open addressing with linear probing over 16-byte slots (a tag
// from the hash, the id, and where the key lies in one contiguous arena of
// copied keys), so that confirming a hit does not chase a pointer into the
// (large, scattered) description.
class NameTable {
 public:
  void reserve(size_t n) {
    size_t cap = 16;
    while (cap < n + n / 2) cap <<= 1;
    slots_.assign(cap, Slot{0, -1, 0, 0});
    mask_ = cap - 1;
    arena_.reserve(n * 8);
    byId_.reserve(n);
  }
  // Returns the id already stored under the name, or stores `id` and returns -1.
  int insert(std::string_view key, int id) {
    if ((count_ + 1) * 3 > slots_.size() * 2) grow();
    const uint64_t h = hashName(key);
    const uint32_t tag = static_cast<uint32_t>(h >> 32);
    size_t i = h & mask_;
    for (; slots_[i].id >= 0; i = (i + 1) & mask_)
      if (matches(slots_[i], tag, key)) return slots_[i].id;
    slots_[i] = {tag, id, static_cast<uint32_t>(arena_.size()), static_cast<uint32_t>(key.size())};
    if (static_cast<size_t>(id) >= byId_.size()) byId_.resize(static_cast<size_t>(id) + 1, {0, kNoKey});
    byId_[id] = {slots_[i].offset, slots_[i].size};
    arena_.append(key);
    ++count_;
    return -1;
  }
  // The key stored for an id (a copy in the arena), if any.
  bool name(int id, std::string_view& out) const {
    if (id < 0 || static_cast<size_t>(id) >= byId_.size() || byId_[id].second == kNoKey) return false;
    out = std::string_view(arena_).substr(byId_[id].first, byId_[id].second);
    return true;
  }
  int find(std::string_view key) const {
    if (slots_.empty()) return -1;
    const uint64_t h = hashName(key);
    const uint32_t tag = static_cast<uint32_t>(h >> 32);
    for (size_t i = h & mask_; slots_[i].id >= 0; i = (i + 1) & mask_)
      if (matches(slots_[i], tag, key)) return slots_[i].id;
    return -1;
  }

 private:
  struct Slot {
    uint32_t tag;
    int32_t id;
    uint32_t offset, size;
  };
  bool matches(const Slot& s, uint32_t tag, std::string_view key) const {
    return s.tag == tag && s.size == key.size() && std::memcmp(arena_.data() + s.offset, key.data(), s.size) == 0;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<size_t>(16, old.size() * 2), Slot{0, -1, 0, 0});
    mask_ = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.id < 0) continue;
      size_t i = hashName(std::string_view(arena_).substr(s.offset, s.size)) & mask_;
      while (slots_[i].id >= 0) i = (i + 1) & mask_;
      slots_[i] = s;
    }
  }
  static constexpr uint32_t kNoKey = 0xFFFFFFFFu;
  std::vector<Slot> slots_;
  std::vector<std::pair<uint32_t, uint32_t>> byId_;  // id -> (offset, size) in the arena
  std::string arena_;
  size_t mask_ = 0, count_ = 0;
};

}  // namespace rgraph::graph_detail
