// The graph compiler, step 7: lifetimes over the execution order, then
// greedy aliasing by first use. See compile.cpp for the outline.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "compile_internal.h"

namespace rgraph::graph_detail {

namespace {

// Aliasing pools: resources may share a physical only with identical keys.
struct PoolKey {
  ResourceKind kind;
  Format format;
  uint32_t width, height, mips, samples, layers;
  bool cube;
  uint64_t bytes;  // buffers
  bool operator==(const PoolKey& o) const {
    return kind == o.kind && format == o.format && width == o.width && height == o.height && mips == o.mips &&
           samples == o.samples && layers == o.layers && cube == o.cube && bytes == o.bytes;
  }
};
struct PoolKeyHash {
  size_t operator()(const PoolKey& k) const {
    uint64_t h = static_cast<uint64_t>(k.kind) * 0x9E3779B97F4A7C15ull;
    auto mix = [&](uint64_t v) { h = (h ^ v) * 0xBF58476D1CE4E5B9ull; h ^= h >> 31; };
    mix(static_cast<uint64_t>(k.format));
    mix(k.width);
    mix(k.height);
    mix((uint64_t{k.mips} << 32) | k.samples);
    mix((uint64_t{k.layers} << 1) | (k.cube ? 1u : 0u));
    mix(k.bytes);
    return static_cast<size_t>(h);
  }
};

}  // namespace

// Buffers are pooled like textures: two buffers share one physical buffer when
// their sizes are equal and their lifetimes do not overlap.
void Compiler::lifetimesAndAliasing() {
  std::vector<uint32_t> byFirst;
  byFirst.reserve(nRes_);
  for (uint32_t i = 0; i < plan_.order.size(); ++i) {
    const uint32_t p = plan_.order[i].value();
    for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
      if (u_[f].res < 0) continue;
      // A lowered description (subresources): every cell of a texture lives
      // and is aliased as its unit's first cell.
      const int r = units_ ? static_cast<int>(units_->rep[units_->of[u_[f].res]]) : u_[f].res;
      Res& rs = r_[r];
      if (rs.first < 0) {
        rs.first = static_cast<int>(i);
        byFirst.push_back(static_cast<uint32_t>(r));
      }
      rs.last = static_cast<int>(i);
    }
  }
  struct Pool {
    std::priority_queue<std::pair<int, int>, std::vector<std::pair<int, int>>, std::greater<>> busy;  // (last, phys)
    std::priority_queue<int, std::vector<int>, std::greater<>> free;
  };
  std::vector<Pool> pools;
  std::unordered_map<PoolKey, int, PoolKeyHash> poolOf;
  plan_.physical.reserve(o_.alias ? byFirst.size() / 4 + 16 : byFirst.size());
  for (uint32_t r : byFirst) {
    Res& rs = r_[r];
    if (rs.imported || !rs.valid) continue;
    plan_.naiveBytes += rs.bytes;
    const bool own = wholeFrame(r);  // a live history or its source: never aliased
    PoolKey key{rs.kind, Format::rgba8, 0, 0, 0, 0, 0, false, 0};
    if (rs.kind == ResourceKind::texture)
      key = {rs.kind, rs.format, rs.extent.width, rs.extent.height, rs.mips, rs.samples, rs.layers, rs.cube, 0};
    else
      key.bytes = rs.bytes;
    int phys = -1;
    Pool* pool = nullptr;
    if (o_.alias && !own) {
      auto [it, inserted] = poolOf.try_emplace(key, static_cast<int>(pools.size()));
      if (inserted) pools.emplace_back();
      pool = &pools[it->second];
      while (!pool->busy.empty() && pool->busy.top().first < rs.first) {
        // Reversed (alias-shuffle): negated, so that the min-heap gives the highest.
        pool->free.push(o_.reverseAliasing ? -pool->busy.top().second : pool->busy.top().second);
        pool->busy.pop();
      }
      if (!pool->free.empty()) {
        phys = o_.reverseAliasing ? -pool->free.top() : pool->free.top();
        pool->free.pop();
      }
    }
    if (phys < 0) {
      phys = static_cast<int>(plan_.physical.size());
      PhysicalTexture& pt = plan_.physical.emplace_back();
      pt.kind = rs.kind;
      pt.bytes = rs.bytes;
      if (rs.kind == ResourceKind::texture) {
        pt.format = rs.format;
        pt.extent = rs.extent;
        pt.mips = rs.mips;
        pt.samples = rs.samples;
        pt.layers = rs.layers;
        pt.cube = rs.cube;
      }
      plan_.allocatedBytes += pt.bytes;
    }
    plan_.physical[phys].resources.push_back(ResourceIndex(units_ ? units_->of[r] : r));
    rs.physical = phys;
    if (pool) pool->busy.push({rs.last, phys});
  }
  peakLiveBytes(byFirst);
  if (units_)
    for (uint32_t r = 0; r < nRes_; ++r) {
      const Res& rep = r_[units_->rep[units_->of[r]]];
      r_[r].first = rep.first, r_[r].last = rep.last, r_[r].physical = rep.physical;
    }
}

// Bytes live at each pass of the order (a whole-frame resource at all of
// them), as differences at lifetime ends; the peak is the largest prefix sum.
void Compiler::peakLiveBytes(const std::vector<uint32_t>& used) {
  const size_t n = plan_.order.size();
  if (n == 0) return;
  std::vector<int64_t> change(n + 1, 0);
  for (uint32_t r : used) {
    const Res& rs = r_[r];
    if (rs.imported || !rs.valid) continue;
    const bool own = wholeFrame(r);
    change[own ? 0 : static_cast<size_t>(rs.first)] += static_cast<int64_t>(rs.bytes);
    change[own ? n : static_cast<size_t>(rs.last) + 1] -= static_cast<int64_t>(rs.bytes);
  }
  int64_t live = 0;
  for (size_t i = 0; i < n; ++i) {
    live += change[i];
    plan_.peakLiveBytes = std::max(plan_.peakLiveBytes, static_cast<uint64_t>(live));
  }
}

}  // namespace rgraph::graph_detail
