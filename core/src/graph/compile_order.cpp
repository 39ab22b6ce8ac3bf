// The graph compiler, steps 5 and 6: the execution order (Kahn with a
// min-heap on declaration index), cycles, and culling. See compile.cpp for
// the outline.
#include <algorithm>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "compile_internal.h"

namespace rgraph::graph_detail {

void Compiler::order() {
  std::vector<uint32_t> adjBegin(nPass_ + 1, 0), indeg(nPass_, 0);
  for (const auto& [a, b] : edges_) {
    ++adjBegin[a + 1];
    ++indeg[b];
  }
  for (uint32_t p = 0; p < nPass_; ++p) adjBegin[p + 1] += adjBegin[p];
  std::vector<uint32_t> adj(edges_.size());
  {
    std::vector<uint32_t> cursor(adjBegin.begin(), adjBegin.end() - 1);
    for (const auto& [a, b] : edges_) adj[cursor[a]++] = static_cast<uint32_t>(b);
  }
  std::vector<uint32_t> heapStore;
  heapStore.reserve(nPass_);
  std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<uint32_t>> ready(std::greater<uint32_t>(),
                                                                                   std::move(heapStore));
  uint32_t enabledCount = 0;
  for (uint32_t p = 0; p < nPass_; ++p)
    if (passFlags_[p] & kEnabled) {
      ++enabledCount;
      if (indeg[p] == 0) ready.push(p);
    }
  topo_.reserve(enabledCount);
  if (o_.reorderSeed != 0) {
    // `reorder` (rgraph/hazards.h): any ready pass may go next; a seeded
    // draw picks it, so that the order is another valid one, the same for a seed.
    std::vector<uint32_t> pool;
    while (!ready.empty()) pool.push_back(ready.top()), ready.pop();
    uint64_t state = o_.reorderSeed;
    while (!pool.empty()) {
      state += 0x9E3779B97F4A7C15ull;  // splitmix64
      uint64_t z = state;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      const size_t pick = static_cast<size_t>(z % pool.size());
      const uint32_t p = pool[pick];
      pool[pick] = pool.back();
      pool.pop_back();
      topo_.push_back(p);
      for (uint32_t i = adjBegin[p]; i < adjBegin[p + 1]; ++i)
        if (--indeg[adj[i]] == 0) pool.push_back(adj[i]);
    }
  }
  while (!ready.empty()) {
    const uint32_t p = ready.top();
    ready.pop();
    topo_.push_back(p);
    for (uint32_t i = adjBegin[p]; i < adjBegin[p + 1]; ++i)
      if (--indeg[adj[i]] == 0) ready.push(adj[i]);
  }
  if (topo_.size() < enabledCount) {
    cyclic_ = true;
    reportCycles(indeg);
  }
}

void Compiler::reportCycles(const std::vector<uint32_t>& indeg) {
  // Every pass left over has a predecessor that is left over too: walking
  // backwards along the lowest-index such predecessor must close a cycle.
  std::vector<char> left(nPass_, 0);
  for (uint32_t p = 0; p < nPass_; ++p) left[p] = (passFlags_[p] & kEnabled) && indeg[p] > 0;
  std::vector<int> pred(nPass_, -1);
  for (const auto& [a, b] : edges_)
    if (left[a] && left[b] && (pred[b] < 0 || a < pred[b])) pred[b] = a;
  std::vector<int> walk(nPass_, 0), pos(nPass_, -1);
  std::vector<int> path;
  int walkId = 0;
  for (uint32_t s = 0; s < nPass_; ++s) {
    if (!left[s] || walk[s]) continue;
    ++walkId;
    path.clear();
    int cur = static_cast<int>(s);
    while (cur >= 0 && walk[cur] == 0) {
      walk[cur] = walkId;
      pos[cur] = static_cast<int>(path.size());
      path.push_back(cur);
      cur = pred[cur];
    }
    if (cur < 0 || walk[cur] != walkId) continue;  // joined an earlier walk: nothing new
    // path[pos[cur]..] walks backwards along the cycle; reverse it to run forwards.
    std::vector<int> cyc(path.begin() + pos[cur], path.end());
    std::reverse(cyc.begin(), cyc.end());
    std::rotate(cyc.begin(), std::min_element(cyc.begin(), cyc.end()), cyc.end());
    std::string msg = "cycle: ";
    for (int p : cyc) msg += passName(p) + " -> ";
    msg += passName(cyc.front());
    msg += " (each pass must run after the one before it: it reads a version that pass writes, or that pass "
           "overwrites a version it reads)";
    diag(DiagCode::cycle, std::move(msg), passName(cyc.front()), {}, {}, d_.passes[cyc.front()].where);
  }
}

// A pass that runs and reads a history H of X needs X written in this frame,
// for the next: the writer of X's last version is kept (with what it reads)
// even when nothing else in the frame reads X. A second phase after the
// frame's own culling, so that the passes kept only for the next frame are
// known (keptFor_, their reason). History reads of culled passes keep nothing.
void Compiler::keepHistorySources(std::vector<uint32_t>& stack) {
  keptFor_.assign(nPass_, -1);
  auto mark = [&](int p, int h) {
    if (enabled(p) && !needed_[p]) {
      needed_[p] = 1;
      keptFor_[p] = h;
      stack.push_back(static_cast<uint32_t>(p));
    }
  };
  for (uint32_t p = 0; p < nPass_; ++p)
    if (needed_[p]) stack.push_back(p);
  while (!stack.empty()) {
    const uint32_t p = stack.back();
    stack.pop_back();
    for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
      if (const int w = historyWriterRead(f); w >= 0) mark(w, u_[f].res);
      mark(u_[f].rawFrom, keptFor_[p]);
    }
  }
}

// A pass that writes a later version of the output's resource than the
// output: it would overwrite the image (CompileOptions::cull false keeps it culled).
bool Compiler::writesAfterOutput(uint32_t p) const {
  for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f)
    if (u_[f].write && u_[f].writeVer >= 0 && vers_[u_[f].writeVer].afterOutput) return true;
  return false;
}

void Compiler::cull() {
  needed_.assign(nPass_, 0);
  std::vector<uint32_t> stack;
  stack.reserve(nPass_);
  auto mark = [&](int p) {
    if (enabled(p) && !needed_[p]) {
      needed_[p] = 1;
      stack.push_back(static_cast<uint32_t>(p));
    }
  };
  mark(outputWriter_);
  for (uint32_t p = 0; p < nPass_; ++p)
    if ((passFlags_[p] & kSideEffect) || (!o_.cull && !writesAfterOutput(p))) mark(static_cast<int>(p));
  // What a pass writes into a caller's texture (imported, arriving with
  // content; not the output image's resource, whose later versions would
  // overwrite the image) is seen by the caller who owns it: such writers
  // are roots, like the output's.
  const int outputRes = outputVer_ >= 0 ? vers_[outputVer_].res : -1;
  for (uint32_t p = 0; p < nPass_; ++p)
    for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
      const int wv = u_[f].write ? u_[f].writeVer : -1;
      if (wv < 0 || vers_[wv].res < 0 || vers_[wv].res == outputRes) continue;
      if (r_[vers_[wv].res].imported && r_[vers_[wv].res].hasContent) mark(static_cast<int>(p));
    }
  while (!stack.empty()) {
    const uint32_t p = stack.back();
    stack.pop_back();
    for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) mark(u_[f].rawFrom);
  }
  if (historyCount_ > 0) keepHistorySources(stack);
  plan_.order.reserve(topo_.size());
  for (uint32_t p : topo_)
    if (needed_[p]) plan_.order.push_back(PassIndex(p));
  // A pass kept for its side effect that writes a later version of the
  // output's resource would overwrite the image before the frame ends.
  if (outputVer_ < 0) return;
  for (int c = vers_[outputVer_].child; c >= 0; c = vers_[c].child) {
    const int w = vers_[c].writer;
    if (!enabled(w) || !needed_[w]) continue;
    diag(DiagCode::invalid_output,
         "output " + q(d_.output) + " is overwritten by pass " + q(passName(w)) +
             ", which writes the later version " + q(versionName(c)) + " and runs for its side effect; name " +
             q(versionName(c)) + " as the output, or write the side effect's result to another resource",
         passName(w), {}, d_.output, d_.outputWhere);
    break;
  }
}

}  // namespace rgraph::graph_detail
