// Properties over a few hundred random DAGs (fixed seeds): valid topological
// order, culling closed under data dependencies, exact lifetimes, and sound
// aliasing. The expected edges come from the generator, not from compile().
#include <algorithm>
#include <gtest/gtest.h>

#include <set>

#include "graph_builder.h"
#include "random_graph.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

struct Descriptor {
  ResourceKind kind;
  Format format;
  Extent extent;
  uint32_t mips, samples;
  uint64_t bufferBytes;
  bool operator==(const Descriptor& o) const {
    return kind == o.kind && format == o.format && extent == o.extent && mips == o.mips && samples == o.samples &&
           bufferBytes == o.bufferBytes;
  }
};

Descriptor descriptorOf(const ResourceDecl& r, Extent output) {
  if (r.kind == ResourceKind::buffer) return {r.kind, Format::rgba8, {}, 0, 0, r.bufferBytes};
  return {r.kind, r.texture.format, resolveSize(r.texture.size, output), r.texture.mips, r.texture.samples, 0};
}

void checkPlan(const RandomGraph& g, const Plan& plan, const CompileOptions& options, const std::string& what) {
  SCOPED_TRACE(what);
  const GraphDesc& d = g.desc;
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  ASSERT_EQ(plan.passes.size(), d.passes.size());
  ASSERT_EQ(plan.resources.size(), d.resources.size());
  EXPECT_EQ(checkPlanContract(plan), "");
  const auto step = [](int i) { return i < 0 ? StepIndex() : StepIndex(static_cast<uint32_t>(i)); };

  // The order lists every live pass once, consistently with PlannedPass::order.
  std::vector<int> pos(d.passes.size(), -1);
  for (size_t i = 0; i < plan.order.size(); ++i) {
    const uint32_t p = plan.order[i].value();
    ASSERT_LT(p, d.passes.size());
    ASSERT_EQ(pos[p], -1) << "pass listed twice";
    pos[p] = static_cast<int>(i);
  }
  for (size_t p = 0; p < d.passes.size(); ++p) {
    EXPECT_EQ(plan.passes[p].decl, PassIndex(static_cast<uint32_t>(p)));
    EXPECT_EQ(plan.passes[p].order, step(pos[p]));
    EXPECT_EQ(plan.passes[p].culled, pos[p] < 0);
    if (d.passes[p].sideEffect) {
      EXPECT_FALSE(plan.passes[p].culled) << d.passes[p].name;
    }
  }
  // The output's writer is live.
  ASSERT_TRUE(plan.outputResource.valid());
  // Every dependency edge between live passes is respected; a live pass's data
  // producers are live.
  for (const DepEdge& e : g.edges) {
    if (e.raw && pos[e.after] >= 0) {
      EXPECT_GE(pos[e.before], 0) << d.passes[e.before].name << " culled";
    }
    if (pos[e.before] >= 0 && pos[e.after] >= 0) {
      EXPECT_LT(pos[e.before], pos[e.after]) << d.passes[e.before].name << " -> " << d.passes[e.after].name;
    }
  }
  // Lifetimes, recomputed from the bindings and the order.
  std::vector<int> first(d.resources.size(), -1), last(d.resources.size(), -1);
  for (size_t i = 0; i < plan.order.size(); ++i)
    for (const BoundUse& b : plan.uses(plan.order[i])) {
      ASSERT_TRUE(b.resource.valid());
      const uint32_t r = b.resource.value();
      if (first[r] < 0) first[r] = static_cast<int>(i);
      last[r] = static_cast<int>(i);
    }
  uint64_t naive = 0;
  for (size_t r = 0; r < d.resources.size(); ++r) {
    const PlannedResource& pr = plan.resources[r];
    EXPECT_EQ(pr.firstPass, step(first[r])) << pr.name;
    EXPECT_EQ(pr.lastPass, step(last[r])) << pr.name;
    const bool live = first[r] >= 0;
    if (d.resources[r].imported || !live) {
      EXPECT_FALSE(pr.physical.valid()) << pr.name;
    } else {
      EXPECT_TRUE(pr.physical.valid()) << pr.name;
      naive += pr.bytes;
    }
  }
  EXPECT_EQ(plan.naiveBytes, naive);
  // Physicals: identical descriptors, disjoint inclusive lifetimes, back references.
  uint64_t allocated = 0;
  size_t members = 0;
  for (size_t ph = 0; ph < plan.physical.size(); ++ph) {
    const PhysicalTexture& pt = plan.physical[ph];
    ASSERT_FALSE(pt.resources.empty());
    allocated += pt.bytes;
    members += pt.resources.size();
    const Descriptor ref = descriptorOf(d.resources[pt.resources[0].value()], options.output);
    for (size_t i = 0; i < pt.resources.size(); ++i) {
      const uint32_t r = pt.resources[i].value();
      EXPECT_EQ(plan.resources[r].physical, PhysicalIndex(static_cast<uint32_t>(ph)));
      EXPECT_EQ(plan.resources[r].bytes, pt.bytes);
      EXPECT_TRUE(descriptorOf(d.resources[r], options.output) == ref)
          << plan.resources[r].name << " vs " << plan.resource(pt.resources[0]).name;
      if (i > 0) {
        EXPECT_LE(plan.resource(pt.resources[i - 1]).firstPass, plan.resources[r].firstPass);
      }
      for (size_t j = i + 1; j < pt.resources.size(); ++j) {
        const PlannedResource& a = plan.resources[r];
        const PlannedResource& b = plan.resource(pt.resources[j]);
        EXPECT_TRUE(a.lastPass < b.firstPass || b.lastPass < a.firstPass)
            << a.name << " [" << a.firstPass << "," << a.lastPass << "] and " << b.name << " [" << b.firstPass << ","
            << b.lastPass << "] share physical " << ph;
      }
    }
  }
  EXPECT_EQ(plan.allocatedBytes, allocated);
  EXPECT_LE(plan.allocatedBytes, plan.naiveBytes);
  size_t liveTransients = 0;
  for (const auto& pr : plan.resources) liveTransients += pr.physical.valid();
  EXPECT_EQ(members, liveTransients);
  if (!options.alias) {
    EXPECT_EQ(plan.physical.size(), liveTransients);
  }
  // Peak live bytes, step by step (no histories here): the most of the
  // transients' bytes whose lifetimes hold one step; no allocation is below it.
  uint64_t peak = 0;
  for (size_t s = 0; s < plan.order.size(); ++s) {
    uint64_t live = 0;
    for (const auto& pr : plan.resources)
      if (pr.physical.valid() && pr.firstPass.value() <= s && s <= pr.lastPass.value()) live += pr.bytes;
    peak = std::max(peak, live);
  }
  EXPECT_EQ(plan.peakLiveBytes, peak);
  EXPECT_LE(plan.peakLiveBytes, plan.allocatedBytes);
}

TEST(Property, RandomDagsCompileSoundly) {
  size_t culledTotal = 0, sharedTotal = 0;
  for (uint64_t seed = 1; seed <= 300; ++seed) {
    RandomGraphOptions o;
    o.seed = seed;
    o.passes = 1 + static_cast<uint32_t>((seed * 7919) % 60);
    o.resources = 2 * o.passes;
    o.sideEffectProbability = 0.05;
    RandomGraph g = randomGraph(o);
    CompileOptions options;
    options.output = {64 + static_cast<uint32_t>(seed % 5) * 100, 48 + static_cast<uint32_t>(seed % 3) * 50};
    Plan plan = compile(g.desc, options);
    checkPlan(g, plan, options, "seed " + std::to_string(seed));
    if (HasFatalFailure() || HasFailure()) return;
    for (const auto& p : plan.passes) culledTotal += p.culled;
    for (const auto& ph : plan.physical) sharedTotal += ph.resources.size() > 1;
    // Deterministic.
    EXPECT_EQ(compile(g.desc, options).order, plan.order);
    if (seed % 10 == 0) {
      options.alias = false;
      checkPlan(g, compile(g.desc, options), options, "no alias, seed " + std::to_string(seed));
    }
  }
  // The generator exercises culling and aliasing, not just trivial graphs.
  EXPECT_GT(culledTotal, 100u);
  EXPECT_GT(sharedTotal, 100u);
}

TEST(Property, ShuffledDeclarationGivesTheSameLiveSet) {
  for (uint64_t seed = 500; seed < 540; ++seed) {
    RandomGraphOptions o;
    o.seed = seed;
    o.passes = 40;
    o.resources = 80;
    o.shuffle = false;
    RandomGraph inOrder = randomGraph(o);
    o.shuffle = true;
    RandomGraph shuffled = randomGraph(o);
    Plan a = compile(inOrder.desc), b = compile(shuffled.desc);
    ASSERT_TRUE(a.ok() && b.ok());
    std::set<std::string> liveA, liveB;
    for (PassIndex p : a.order) liveA.insert(a.pass(p).name);
    for (PassIndex p : b.order) liveB.insert(b.pass(p).name);
    EXPECT_EQ(liveA, liveB) << seed;
    // Declared in generation order, with no ties broken differently, the
    // order is the declaration order restricted to live passes.
    for (size_t i = 1; i < a.order.size(); ++i) EXPECT_LT(a.order[i - 1], a.order[i]);
  }
}

TEST(Property, LargeGraphCompiles) {
  RandomGraphOptions o;
  o.passes = 2000;
  o.resources = 4000;
  o.seed = 7;
  RandomGraph g = randomGraph(o);
  CompileOptions options;
  checkPlan(g, compile(g.desc, options), options, "large");
}

}  // namespace

// Hazard modes that change the plan (rgraph/hazards.h) give other valid plans:
// `reorder` another topological order of the same passes (every generated
// edge still respected, checkPlan), different from the plain one for most
// graphs; `alias-shuffle` another aliasing with no lifetime overlap (checkPlan),
// different for graphs that alias more than a pair; `no-cull` every pass.
TEST(Property, HazardModePlansAreOtherValidPlans) {
  size_t reordered = 0, reorderable = 0, reshuffled = 0, shufflable = 0;
  for (uint64_t seed = 1; seed <= 120; ++seed) {
    RandomGraphOptions o;
    o.seed = seed;
    o.passes = 2 + static_cast<uint32_t>((seed * 7919) % 40);
    o.resources = 2 * o.passes;
    RandomGraph g = randomGraph(o);
    CompileOptions options;
    options.output = {64, 48};
    const Plan plain = compile(g.desc, options);
    ASSERT_TRUE(plain.ok()) << dumpDiagnostics(plain);
    std::vector<PassIndex> sortedPlain = plain.order;
    std::sort(sortedPlain.begin(), sortedPlain.end());
    bool someOrderDiffers = false;
    for (uint64_t k = 1; k <= 3; ++k) {
      CompileOptions r = options;
      r.reorderSeed = k;
      const Plan reorderedPlan = compile(g.desc, r);
      checkPlan(g, reorderedPlan, r, "reorder " + std::to_string(k) + ", seed " + std::to_string(seed));
      if (HasFailure()) return;
      std::vector<PassIndex> sorted = reorderedPlan.order;
      std::sort(sorted.begin(), sorted.end());
      EXPECT_EQ(sorted, sortedPlain) << "the same passes run, seed " << seed;
      EXPECT_EQ(compile(g.desc, r).order, reorderedPlan.order) << "a seed gives one order";
      someOrderDiffers = someOrderDiffers || reorderedPlan.order != plain.order;
    }
    reorderable += plain.order.size() > 3;
    reordered += plain.order.size() > 3 && someOrderDiffers;

    CompileOptions s = options;
    s.reverseAliasing = true;
    const Plan shuffled = compile(g.desc, s);
    checkPlan(g, shuffled, s, "alias-shuffle, seed " + std::to_string(seed));
    if (HasFailure()) return;
    EXPECT_EQ(shuffled.order, plain.order);
    bool aliasDiffers = false, aliasesMore = false;
    for (size_t r = 0; r < plain.resources.size(); ++r)
      aliasDiffers = aliasDiffers || plain.resources[r].physical != shuffled.resources[r].physical;
    for (const PhysicalTexture& p : plain.physical) aliasesMore = aliasesMore || p.resources.size() > 2;
    shufflable += aliasesMore;
    reshuffled += aliasesMore && aliasDiffers;

    CompileOptions n = options;
    n.cull = false;
    const Plan uncut = compile(g.desc, n);
    checkPlan(g, uncut, n, "no-cull, seed " + std::to_string(seed));
    if (HasFailure()) return;
    for (const PlannedPass& p : uncut.passes) EXPECT_FALSE(p.culled) << p.name << ": " << p.reason;
  }
  // Most graphs that can show it do.
  EXPECT_GT(reordered * 10, reorderable * 9) << reordered << " of " << reorderable;
  EXPECT_GT(reorderable, 60u);
  EXPECT_GT(reshuffled * 2, shufflable) << reshuffled << " of " << shufflable;
  EXPECT_GT(shufflable, 20u);
}
