// Random graphs over parts of textures (fixed seeds), checked against an
// oracle that tracks every mip level x layer element on its own: the plan
// orders every read after the element's writer and every overwrite after the
// element's readers, keeps exactly the passes the output and side effects
// need, and reports nothing; a graph with one hazard injected (a second writer
// of an element, a read of an element nobody wrote) is reported at that pass,
// and with nothing else. Textures: a mip chain with layers, a cube with mips,
// and an array of more layers than get a cell each (runs of layers).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

struct Shape {
  std::string name;
  uint32_t size, mips, layers;  // layers: array layers (6 for the cube)
  bool cube;
};
const std::vector<Shape> kShapes = {{"chain", 64, 3, 4, false}, {"env", 32, 2, 6, true}, {"atlas", 4, 1, 100, false}};

struct Element {
  std::string version;  // current version name, empty: never written
  int writer = -1;
  std::set<int> readers;  // readers of the current version
};

struct Edge {
  int before, after;
  bool raw;
};

enum class Hazard { none, second_writer, unwritten_read };

struct Generated {
  GraphDesc desc;
  std::vector<Edge> edges;
  int hazardPass = -1;
};

class Generator {
 public:
  explicit Generator(uint32_t seed) : rng_(seed) {}

  Generated make(Hazard hazard) {
    Generated g;
    elements_.assign(kShapes.size(), {});
    for (size_t t = 0; t < kShapes.size(); ++t) {
      elements_[t].resize(size_t{kShapes[t].mips} * kShapes[t].layers);
      ResourceDecl r = tex(kShapes[t].name, Format::rgba16f,
                           SizeSpec::absolute(kShapes[t].size, kShapes[t].size), kShapes[t].mips);
      r.texture.cube = kShapes[t].cube;
      r.texture.layers = kShapes[t].cube ? 1 : kShapes[t].layers;
      g.desc.resources.push_back(r);
    }
    const int n = 6 + static_cast<int>(rng_() % 20);
    for (int p = 0; p < n; ++p) {
      PassDecl pd = pass("p" + std::to_string(p), {});
      pd.sideEffect = rng_() % 10 == 0;
      touched_.clear();
      const int uses = 1 + static_cast<int>(rng_() % 3);
      for (int k = 0; k < uses; ++k) addUse(p, pd, g.edges);
      // Every pass writes a texture of its own, so that it may feed the output.
      g.desc.resources.push_back(tex("own" + std::to_string(p), Format::rgba8, SizeSpec::absolute(4, 4)));
      pd.uses.push_back(wr("own", "own" + std::to_string(p), Access::storage_write));
      g.desc.passes.push_back(std::move(pd));
    }
    // The output reads some passes' own textures and some parts.
    PassDecl out = pass("final", {});
    touched_.clear();
    for (int p = 0; p < n; ++p)
      if (rng_() % 3 == 0) {
        out.uses.push_back(rd("own" + std::to_string(p), "own" + std::to_string(p)));
        g.edges.push_back({p, n, true});
      }
    for (int k = 0; k < 2; ++k) addRead(n, out, g.edges);
    g.desc.resources.push_back(tex("out"));
    out.uses.push_back(wr("color", "out", Access::storage_write));
    g.desc.passes.push_back(std::move(out));
    g.desc.output = "out";
    if (hazard != Hazard::none) inject(hazard, g);
    // Declaration order is not execution order: shuffle it (and the edges' indices with it).
    std::vector<int> perm(g.desc.passes.size());
    for (size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
    std::shuffle(perm.begin(), perm.end(), rng_);
    std::vector<PassDecl> shuffled(perm.size());
    for (size_t i = 0; i < perm.size(); ++i) shuffled[perm[i]] = std::move(g.desc.passes[i]);
    g.desc.passes = std::move(shuffled);
    for (Edge& e : g.edges) e.before = perm[e.before], e.after = perm[e.after];
    if (g.hazardPass >= 0) g.hazardPass = perm[g.hazardPass];
    return g;
  }

 private:
  struct Range {
    size_t t;
    Subresource sub;  // resolved
    bool whole;
  };

  Range randomRange() {
    Range r;
    r.t = rng_() % kShapes.size();
    const Shape& s = kShapes[r.t];
    r.whole = rng_() % 6 == 0;
    if (r.whole) {
      r.sub = {0, s.mips, 0, s.layers};
      return r;
    }
    auto span = [&](uint32_t total, uint32_t& b, uint32_t& c) {
      b = static_cast<uint32_t>(rng_() % total);
      c = 1 + static_cast<uint32_t>(rng_() % (rng_() % 2 ? 1 : total - b));
    };
    span(s.mips, r.sub.mipBegin, r.sub.mipCount);
    span(s.layers, r.sub.layerBegin, r.sub.layerCount);
    return r;
  }
  template <class F>
  void each(const Range& r, F f) {
    for (uint32_t m = r.sub.mipBegin; m < r.sub.mipBegin + r.sub.mipCount; ++m)
      for (uint32_t l = r.sub.layerBegin; l < r.sub.layerBegin + r.sub.layerCount; ++l)
        f(elements_[r.t][size_t{m} * kShapes[r.t].layers + l], size_t{m} * kShapes[r.t].layers + l);
  }
  // One version name over the whole range, every element written, none touched by this pass.
  std::string sameVersion(const Range& r) {
    std::string v;
    bool ok = true;
    each(r, [&](Element& e, size_t i) {
      if (e.version.empty() || touched_.count({r.t, i}) || (!v.empty() && e.version != v)) ok = false;
      v = e.version;
    });
    return ok ? v : std::string();
  }
  bool unwritten(const Range& r) {
    bool ok = true;
    each(r, [&](Element& e, size_t i) { ok = ok && e.version.empty() && !touched_.count({r.t, i}); });
    return ok;
  }
  void touch(const Range& r) {
    each(r, [&](Element&, size_t i) { touched_.insert({r.t, i}); });
  }
  ResourceUse use(ResourceUse u, const Range& r) {
    if (!r.whole) {
      u.sub = r.sub;
      if (kShapes[r.t].mips == 1) u.sub.mipCount = Subresource::kAll;
    }
    return u;
  }

  void addRead(int p, PassDecl& pd, std::vector<Edge>& edges) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const Range r = randomRange();
      const std::string v = sameVersion(r);
      if (v.empty()) continue;
      each(r, [&](Element& e, size_t) {
        edges.push_back({e.writer, p, true});
        e.readers.insert(p);
      });
      touch(r);
      pd.uses.push_back(use(rd("r" + std::to_string(pd.uses.size()), v), r));
      return;
    }
  }

  void addUse(int p, PassDecl& pd, std::vector<Edge>& edges) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const Range r = randomRange();
      const int op = static_cast<int>(rng_() % 3);
      const std::string slot = "u" + std::to_string(pd.uses.size());
      if (op == 0 && unwritten(r)) {
        each(r, [&](Element& e, size_t) { e.version = kShapes[r.t].name, e.writer = p; });
        touch(r);
        pd.uses.push_back(use(wr(slot, kShapes[r.t].name, Access::storage_write), r));
        return;
      }
      const std::string v = sameVersion(r);
      if (v.empty()) continue;
      if (op == 1) {
        const std::string next = kShapes[r.t].name + "_v" + std::to_string(p);
        each(r, [&](Element& e, size_t) {
          edges.push_back({e.writer, p, true});
          for (int reader : e.readers)
            if (reader != p) edges.push_back({reader, p, false});
          e.version = next, e.writer = p, e.readers.clear();
        });
        touch(r);
        pd.uses.push_back(use(rmw(slot, v, next, Access::storage_write), r));
        return;
      }
      addRead(p, pd, edges);
      return;
    }
  }

  void inject(Hazard hazard, Generated& g) {
    const int p = static_cast<int>(rng_() % g.desc.passes.size());
    for (int attempt = 0; attempt < 200; ++attempt) {
      const Range r = randomRange();
      std::set<int> writers;
      bool allUnwritten = true;
      each(r, [&](Element& e, size_t) {
        if (e.writer >= 0 && e.writer != p) writers.insert(e.writer);
        allUnwritten = allUnwritten && e.version.empty();
      });
      if (hazard == Hazard::second_writer && !writers.empty()) {
        g.desc.passes[p].uses.push_back(use(wr("extra", kShapes[r.t].name, Access::storage_write), r));
        g.hazardPass = p;
        return;
      }
      if (hazard == Hazard::unwritten_read && allUnwritten) {
        // Reads the first version of elements no pass writes (none written: no edge, no cycle).
        g.desc.passes[p].uses.push_back(use(rd("extra", kShapes[r.t].name), r));
        g.desc.passes[p].sideEffect = true;  // so that the read matters
        g.hazardPass = p;
        return;
      }
    }
  }

  std::mt19937 rng_;
  std::vector<std::vector<Element>> elements_;
  std::set<std::pair<size_t, size_t>> touched_;  // (texture, element) this pass already binds
};

// Passes the output and the side effects need, over data edges.
std::vector<bool> expectedLive(const Generated& g) {
  const size_t n = g.desc.passes.size();
  std::vector<bool> live(n, false);
  std::vector<int> stack;
  for (size_t p = 0; p < n; ++p)
    if (g.desc.passes[p].sideEffect || g.desc.passes[p].name == "final") live[p] = true, stack.push_back(int(p));
  while (!stack.empty()) {
    const int p = stack.back();
    stack.pop_back();
    for (const Edge& e : g.edges)
      if (e.raw && e.after == p && !live[e.before]) live[e.before] = true, stack.push_back(e.before);
  }
  return live;
}

TEST(SubresourceProperty, RandomGraphsOrderAndCullPerElement) {
  int parts = 0;
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    Generator gen(seed);
    const Generated g = gen.make(Hazard::none);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Plan plan = compile(g.desc);
    ASSERT_TRUE(plan.diagnostics.empty()) << dumpDiagnostics(plan);  // none invented
    EXPECT_EQ(checkPlanContract(plan), "");
    const std::vector<bool> live = expectedLive(g);
    for (size_t p = 0; p < g.desc.passes.size(); ++p)
      EXPECT_EQ(!plan.passes[p].culled, live[p]) << g.desc.passes[p].name << ": " << plan.passes[p].reason;
    for (const Edge& e : g.edges) {
      const StepIndex a = plan.passes[e.before].order, b = plan.passes[e.after].order;
      if (a.valid() && b.valid())
        EXPECT_LT(a, b) << g.desc.passes[e.before].name << " -> " << g.desc.passes[e.after].name;
    }
    // Bindings carry the config's names and resolved ranges within the texture.
    for (size_t p = 0; p < g.desc.passes.size(); ++p)
      for (size_t i = 0; i < g.desc.passes[p].uses.size(); ++i) {
        const ResourceUse& u = g.desc.passes[p].uses[i];
        const BoundUse& b = plan.bindings[p][i];
        EXPECT_EQ(b.slot, u.slot);
        EXPECT_NE(b.sub.mipCount, Subresource::kAll);
        if (!u.sub.whole()) {
          ++parts;
          EXPECT_EQ(b.sub.layerBegin, u.sub.layerBegin);
        }
      }
  }
  EXPECT_GT(parts, 1000);  // the generator binds parts, not only whole textures
}

TEST(SubresourceProperty, EveryInjectedHazardIsReportedAtItsPass) {
  for (Hazard hazard : {Hazard::second_writer, Hazard::unwritten_read})
    for (uint32_t seed = 1; seed <= 150; ++seed) {
      Generator gen(seed * 7919);
      const Generated g = gen.make(hazard);
      if (g.hazardPass < 0) continue;
      SCOPED_TRACE("seed " + std::to_string(seed) + (hazard == Hazard::second_writer ? " second writer" : " unread"));
      const Plan plan = compile(g.desc);
      const DiagCode code =
          hazard == Hazard::second_writer ? DiagCode::duplicate_writer : DiagCode::read_never_written;
      ASSERT_FALSE(plan.ok());
      bool atPass = false;
      for (const Diagnostic& d : plan.diagnostics) {
        // Nothing else is wrong; but when the second writer is declared first it
        // holds the version, and the readers' order may then close a cycle.
        if (d.code == DiagCode::cycle && hazard == Hazard::second_writer) continue;
        EXPECT_EQ(d.code, code) << formatDiagnostic(d);
        const std::string& name = g.desc.passes[g.hazardPass].name;
        // A second writer declared before the first is reported at the first, naming the second.
        if (d.pass == name || d.message.find("'" + name + "'") != std::string::npos) atPass = true;
      }
      EXPECT_TRUE(atPass) << dumpDiagnostics(plan);
    }
}

}  // namespace
