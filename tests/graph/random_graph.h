// A reproducible random render graph (a DAG by construction) together with the
// dependency edges it implies, computed independently of the compiler. Used by
// the property tests and by bench/graph_compile.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph::testgen {

struct RandomGraphOptions {
  uint32_t passes = 100;
  uint32_t resources = 200;
  uint64_t seed = 1;
  double inPlaceProbability = 0.3;     // a write modifies an existing resource (new version)
  double secondWriteProbability = 0.4; // a pass writes 2 resources instead of 1
  double bufferProbability = 0.1;
  double importedProbability = 0.03;   // imported with content: readable with no writer
  double sideEffectProbability = 0.02;
  bool shuffle = true;                 // declare passes in a random (non-topological) order
};

// `before` must run before `after` (indices into desc.passes). `raw`: the
// edge carries data (after reads what before wrote); otherwise write-after-read.
struct DepEdge {
  uint32_t before, after;
  bool raw;
};

struct RandomGraph {
  GraphDesc desc;
  std::vector<DepEdge> edges;
};

// splitmix64: the same sequence on every platform and standard library.
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  uint32_t below(uint32_t n) { return n == 0 ? 0 : static_cast<uint32_t>(next() % n); }
  bool chance(double p) { return static_cast<double>(next() >> 11) * 0x1.0p-53 < p; }

 private:
  uint64_t s_;
};

inline RandomGraph randomGraph(const RandomGraphOptions& o) {
  Rng rng(o.seed);
  RandomGraph g;
  GraphDesc& d = g.desc;
  const Format formats[] = {Format::rgba8, Format::rgba16f, Format::r16f};

  struct State {
    std::string latest;  // name of the latest version, empty while unwritten
    int writer = -1;     // generation index of the latest version's writer, -1 external
    uint32_t versions = 0;
    std::vector<uint32_t> readers;  // readers of the latest version
  };
  std::vector<State> st(o.resources);
  std::vector<uint32_t> available;  // resources with a readable latest version
  std::vector<uint32_t> recent;     // resources by time of last write (may repeat)
  std::vector<uint32_t> unwritten;  // transient resources nobody has written yet, in order

  d.resources.resize(o.resources);
  for (uint32_t r = 0; r < o.resources; ++r) {
    ResourceDecl& rd = d.resources[r];
    rd.name = "r" + std::to_string(r);
    // r0 is a transient texture, written first: every graph writes an image to name as its output.
    const bool isBuffer = rng.chance(o.bufferProbability) && r != 0;
    if (isBuffer) {
      rd.kind = ResourceKind::buffer;
      rd.bufferBytes = rng.chance(0.5) ? 1024 : 4096;
    } else {
      rd.texture.format = formats[rng.below(3)];
      rd.texture.size = rng.chance(0.7) ? SizeSpec::output() : SizeSpec::relative(0.5f);
    }
    if (rng.chance(o.importedProbability) && r != 0) {
      rd.imported = true;
      rd.importedHasContent = true;
      st[r].latest = rd.name;
      st[r].versions = 1;
      available.push_back(r);
      recent.push_back(r);
    } else {
      unwritten.push_back(r);
    }
  }
  std::reverse(unwritten.begin(), unwritten.end());  // pop_back yields r0 first

  auto pick = [&]() -> uint32_t {
    if (!recent.empty() && rng.chance(0.7)) {
      uint32_t window = std::min<uint32_t>(16, static_cast<uint32_t>(recent.size()));
      return recent[recent.size() - 1 - rng.below(window)];
    }
    return available[rng.below(static_cast<uint32_t>(available.size()))];
  };

  std::vector<PassDecl> gen(o.passes);
  int lastWritten = -1;
  std::vector<uint32_t> touched;
  for (uint32_t p = 0; p < o.passes; ++p) {
    PassDecl& pd = gen[p];
    pd.name = "pass" + std::to_string(p);
    pd.type = "random";
    pd.sideEffect = rng.chance(o.sideEffectProbability);
    touched.clear();
    auto isTouched = [&](uint32_t r) { return std::find(touched.begin(), touched.end(), r) != touched.end(); };
    // Reads of latest versions.
    uint32_t nReads = available.empty() ? 0 : rng.below(4);
    for (uint32_t i = 0; i < nReads; ++i) {
      uint32_t r = pick();
      if (isTouched(r)) continue;
      touched.push_back(r);
      ResourceUse u;
      u.slot = "in" + std::to_string(i);
      u.access = d.resources[r].kind == ResourceKind::buffer ? Access::storage_read : Access::sampled;
      u.input = st[r].latest;
      pd.uses.push_back(std::move(u));
      if (st[r].writer >= 0) g.edges.push_back({static_cast<uint32_t>(st[r].writer), p, true});
      st[r].readers.push_back(p);
    }
    // Writes: fresh first versions or in-place successors.
    uint32_t nWrites = rng.chance(o.secondWriteProbability) ? 2 : 1;
    for (uint32_t i = 0; i < nWrites; ++i) {
      ResourceUse u;
      u.slot = "out" + std::to_string(i);
      uint32_t r = 0;
      bool inPlace = unwritten.empty() || (!available.empty() && rng.chance(o.inPlaceProbability));
      if (inPlace) {
        if (available.empty()) break;
        r = pick();
        if (isTouched(r)) continue;
        State& s = st[r];
        u.input = s.latest;
        u.output = d.resources[r].name + "_v" + std::to_string(s.versions);
        if (s.writer >= 0) g.edges.push_back({static_cast<uint32_t>(s.writer), p, true});
        for (uint32_t reader : s.readers)
          if (reader != p) g.edges.push_back({reader, p, false});
      } else {
        r = unwritten.back();
        unwritten.pop_back();
        u.output = d.resources[r].name;
        available.push_back(r);
      }
      touched.push_back(r);
      State& s = st[r];
      s.latest = u.output;
      s.writer = static_cast<int>(p);
      s.readers.clear();
      ++s.versions;
      recent.push_back(r);
      if (d.resources[r].kind == ResourceKind::texture) lastWritten = static_cast<int>(r);  // an output is an image
      const bool buffer = d.resources[r].kind == ResourceKind::buffer;
      u.access = buffer ? Access::storage_write : (i == 0 ? Access::color_attachment : Access::storage_write);
      pd.uses.push_back(std::move(u));
    }
  }
  // The last written texture's latest version (a resource's name is its first version).
  d.output = lastWritten >= 0 ? st[lastWritten].latest : std::string();

  // Declaration order: a random permutation of the generation order.
  std::vector<uint32_t> declOf(o.passes);
  for (uint32_t p = 0; p < o.passes; ++p) declOf[p] = p;
  if (o.shuffle)
    for (uint32_t i = o.passes; i > 1; --i) std::swap(declOf[i - 1], declOf[rng.below(i)]);
  d.passes.resize(o.passes);
  for (uint32_t p = 0; p < o.passes; ++p) d.passes[declOf[p]] = std::move(gen[p]);
  for (DepEdge& e : g.edges) {
    e.before = declOf[e.before];
    e.after = declOf[e.after];
  }
  return g;
}

}  // namespace rgraph::testgen
