// History resources (ResourceDecl::historyOf): a resource holding the previous
// frame's content of another. Nobody in the frame writes it; reading it orders
// nothing; a pass that runs and reads it keeps its source's writers (a pass
// that only feeds the next frame is not culled); it and its source live for
// the whole frame in textures of their own; and every misuse is a
// history_error at the declaration.
#include <gtest/gtest.h>

#include <algorithm>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;
using Strings = std::vector<std::string>;

namespace {

ResourceDecl historyOf(std::string name, std::string source, Format f = Format::rgba16f) {
  ResourceDecl r = tex(std::move(name), f);
  r.historyOf = std::move(source);
  r.historyWhere = at(7, 20, "/resources/" + r.name + "/history_of");
  r.where = at(7, 5, "/resources/" + r.name);
  return r;
}

// render -> scene; taa reads scene and resolved_prev (the history of
// resolved), writes resolved; present reads resolved into the output.
GraphDesc taaGraph() {
  GraphDesc d;
  d.resources = {tex("scene", Format::rgba16f), tex("resolved", Format::rgba16f),
                 historyOf("resolved_prev", "resolved"), importedTex("out", false)};
  d.passes = {
      pass("render", {wr("color", "scene")}),
      pass("taa", {rd("current", "scene"), rd("history", "resolved_prev"), wr("color", "resolved")}),
      pass("present", {rd("src", "resolved"), wr("color", "out")}),
  };
  d.output = "out";
  return d;
}

// The first history_error of compiling d (a test failure when there is none).
Diagnostic historyErrorOf(const GraphDesc& d) {
  const Plan plan = compile(d);
  auto e = withCode(plan, DiagCode::history_error);
  if (e.empty()) {
    ADD_FAILURE() << "no history_error:\n" << dumpDiagnostics(plan);
    return {};
  }
  return *e.front();
}

TEST(History, TaaGraphCompilesAndLinksHistoryToItsSource) {
  Plan plan = compile(taaGraph());
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"render", "taa", "present"}));
  const int resolved = resourceIndex(plan, "resolved"), prev = resourceIndex(plan, "resolved_prev");
  EXPECT_EQ(res(plan, "resolved_prev").historyOf, ResourceIndex(resolved));
  EXPECT_EQ(res(plan, "resolved").history, ResourceIndex(prev));
  EXPECT_FALSE(res(plan, "scene").history.valid());
  EXPECT_FALSE(res(plan, "scene").historyOf.valid());
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(History, ReadAddsNoEdgeSoTheReaderMayRunBeforeTheSourcesWriter) {
  // "blend" reads last frame's "x" and is declared first; "make_x" writes
  // this frame's. A same-frame edge make_x -> blend would put blend second.
  GraphDesc d;
  d.resources = {tex("x", Format::rgba16f), historyOf("x_prev", "x"), tex("blended", Format::rgba16f),
                 importedTex("out", false)};
  d.passes = {
      pass("blend", {rd("prev", "x_prev"), wr("color", "blended")}),
      pass("make_x", {wr("color", "x")}),
      pass("present", {rd("a", "blended"), rd("b", "x"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"blend", "make_x", "present"}));
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(History, PassReadingTheHistoryOfWhatItWritesIsNoCycleNorFeedbackLoop) {
  // taa reads resolved_prev and writes resolved: two textures, no cycle.
  Plan plan = compile(taaGraph());
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_TRUE(withCode(plan, DiagCode::cycle).empty());
  EXPECT_TRUE(withCode(plan, DiagCode::feedback_loop).empty());
  EXPECT_TRUE(withCode(plan, DiagCode::read_never_written).empty()) << "version 0 of a history is readable";
}

TEST(History, HistoryAndSourceLiveForTheWholeFrame) {
  GraphDesc d = taaGraph();
  // Passes before and after taa: without history, resolved would live from
  // taa to present only, resolved_prev at taa only.
  d.resources.push_back(tex("pre", Format::rgba8));
  d.resources.push_back(tex("post", Format::rgba8));
  d.passes.insert(d.passes.begin(), pass("early", {wr("color", "pre")}));
  d.passes[1].uses.push_back(rd("pre", "pre"));  // render reads pre
  d.passes.push_back(pass("late", {rd("src", "resolved"), wr("color", "post")}, /*sideEffect=*/true));
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  ASSERT_EQ(orderNames(plan), (Strings{"early", "render", "taa", "present", "late"}));
  const StepIndex first(0), last(4);
  for (const char* name : {"resolved", "resolved_prev"}) {
    EXPECT_EQ(res(plan, name).firstPass, first) << name;
    EXPECT_EQ(res(plan, name).lastPass, last) << name;
  }
  EXPECT_EQ(res(plan, "scene").firstPass, StepIndex(1)) << "ordinary resources keep their own lifetimes";
  EXPECT_EQ(res(plan, "scene").lastPass, StepIndex(2));
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(History, PassThatOnlyFeedsTheNextFrameIsNotCulled) {
  // Nothing in this frame reads "x"; "use" reads its history. "make_x" (and
  // "base", which make_x reads) run for the next frame.
  GraphDesc d;
  d.resources = {tex("base"), tex("x"), historyOf("x_prev", "x", Format::rgba8), importedTex("out", false)};
  d.passes = {
      pass("base_pass", {wr("color", "base")}),
      pass("make_x", {rd("src", "base"), wr("color", "x")}),
      pass("use", {rd("prev", "x_prev"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"base_pass", "make_x", "use"}));
  for (const char* name : {"base_pass", "make_x"}) {
    const PlannedPass& p = plan.passes[passIndex(plan, name)];
    EXPECT_FALSE(p.culled) << name;
    EXPECT_NE(p.reason.find("history 'x_prev'"), std::string::npos) << name << ": " << p.reason;
    EXPECT_NE(p.reason.find("next frame"), std::string::npos) << p.reason;
  }
  EXPECT_EQ(plan.passes[passIndex(plan, "use")].reason, "") << "kept for this frame: no reason";
  EXPECT_TRUE(res(plan, "x").history.valid());
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(History, HistoryReadByACulledPassKeepsNothingAlive) {
  // "debug" reads x_prev but nothing reads what it writes: it is culled, and
  // so is make_x, which feeds only x_prev.
  GraphDesc d;
  d.resources = {tex("x"), historyOf("x_prev", "x", Format::rgba8), tex("dbg"), importedTex("out", false)};
  d.passes = {
      pass("make_x", {wr("color", "x")}),
      pass("debug", {rd("prev", "x_prev"), wr("color", "dbg")}),
      pass("main", {wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"main"}));
  EXPECT_TRUE(plan.passes[passIndex(plan, "make_x")].culled);
  EXPECT_TRUE(plan.passes[passIndex(plan, "debug")].culled);
  EXPECT_FALSE(res(plan, "x_prev").physical.valid());
  EXPECT_FALSE(res(plan, "x").history.valid()) << "not read by a pass that runs: nothing to keep";
  EXPECT_FALSE(res(plan, "x_prev").historyOf.valid());
  EXPECT_EQ(checkPlanContract(plan), "");
}

// a -> b -> c -> d, all rgba8 at output size; x is written first and read
// second: in a plain graph x's texture is reused by the transients after it.
GraphDesc aliasChain(bool keepHistory) {
  GraphDesc d;
  d.resources = {tex("x"), tex("t1"), tex("t2"), tex("t3"), importedTex("out", false)};
  d.passes = {
      pass("make_x", {wr("color", "x")}),
      pass("p1", {rd("src", "x"), wr("color", "t1")}),
      pass("p2", {rd("src", "t1"), wr("color", "t2")}),
      pass("p3", {rd("src", "t2"), wr("color", "t3")}),
      pass("present", {rd("src", "t3"), wr("color", "out")}),
  };
  if (keepHistory) {
    d.resources.push_back(historyOf("x_prev", "x", Format::rgba8));
    d.passes[3].uses.push_back(rd("prev", "x_prev"));
  }
  d.output = "out";
  return d;
}

TEST(History, HistoryAndSourceAreNeverAliased) {
  Plan plain = compile(aliasChain(false));
  ASSERT_TRUE(plain.ok()) << dumpDiagnostics(plain);
  const PhysicalIndex xPlain = res(plain, "x").physical;
  ASSERT_TRUE(xPlain.valid());
  EXPECT_GT(plain.physicalTexture(xPlain).resources.size(), 1u) << "the chain aliases with x in a plain graph";

  Plan plan = compile(aliasChain(true));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  for (const char* name : {"x", "x_prev"}) {
    const PhysicalIndex p = res(plan, name).physical;
    ASSERT_TRUE(p.valid()) << name;
    ASSERT_EQ(plan.physicalTexture(p).resources.size(), 1u) << name << " shares its texture";
  }
  EXPECT_NE(res(plan, "x").physical, res(plan, "x_prev").physical);
  // The transients still alias among themselves: t1 and t3 share.
  EXPECT_EQ(res(plan, "t1").physical, res(plan, "t3").physical);
  const uint64_t tex1 = res(plan, "x").bytes;
  EXPECT_EQ(plan.naiveBytes, plain.naiveBytes + tex1) << "naive counts the history too";
  EXPECT_EQ(plan.allocatedBytes, 4 * tex1) << "x, x_prev, and two for the chain";
  EXPECT_EQ(plan.peakLiveBytes, 4 * tex1) << "x and x_prev live the whole frame, with two of the chain";
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(History, ContractCatchesAnAliasedHistory) {
  Plan plan = compile(aliasChain(true));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  // Break the plan the way a wrong aliasing step would: t1 moves into x_prev's texture.
  const int t1 = resourceIndex(plan, "t1");
  const PhysicalIndex prev = res(plan, "x_prev").physical, old = res(plan, "t1").physical;
  auto& oldList = plan.physical[old.value()].resources;
  oldList.erase(std::find(oldList.begin(), oldList.end(), ResourceIndex(t1)));
  plan.physical[prev.value()].resources.push_back(ResourceIndex(t1));
  plan.resources[t1].physical = prev;
  EXPECT_NE(checkPlanContract(plan).find("does not own its physical"), std::string::npos) << checkPlanContract(plan);
}

TEST(History, DotDrawsANextFrameEdgeIntoTheHistory) {
  GraphDesc d = taaGraph();
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  const std::string dot = toDot(d, plan);
  EXPECT_NE(dot.find("label=\"resolved_prev\\n(history of resolved)"), std::string::npos) << dot;
  // resolved is version node v1 (declaration order), resolved_prev v2.
  EXPECT_NE(dot.find("v1 -> v2 [style=dashed, color=\"#1f78b4\", fontcolor=\"#1f78b4\", constraint=false, "
                     "label=\"next frame\"];"),
            std::string::npos)
      << dot;
}

// ---------------------------------------------------------------- diagnostics

TEST(HistoryDiagnostics, UnknownSourceSuggestsTheClosestName) {
  GraphDesc d = taaGraph();
  d.resources[2].historyOf = "resolvd";
  Diagnostic e = historyErrorOf(d);
  EXPECT_EQ(e.where.line, 7);
  EXPECT_EQ(e.where.column, 20) << "at the \"history_of\" value";
  EXPECT_EQ(e.where.path, "/resources/resolved_prev/history_of");
  EXPECT_NE(e.message.find("'resolvd', which is not a declared resource (did you mean 'resolved'?)"), std::string::npos)
      << e.message;
}

TEST(HistoryDiagnostics, SourceMustBeAResourceNotAVersion) {
  GraphDesc d = taaGraph();
  d.resources.push_back(tex("lit"));
  d.passes.insert(d.passes.begin() + 1, pass("bloom", {rmw("color", "scene", "scene_bloomed")}));
  d.passes[2].uses[0].input = "scene_bloomed";
  d.resources[2].historyOf = "scene_bloomed";
  d.resources[2].texture.format = Format::rgba16f;
  Diagnostic e = historyErrorOf(d);
  EXPECT_NE(e.message.find("a version of resource 'scene', not a resource"), std::string::npos) << e.message;
}

TEST(HistoryDiagnostics, SourceNobodyWrites) {
  GraphDesc d = taaGraph();
  d.resources.push_back(tex("never", Format::rgba16f));
  d.resources[2].historyOf = "never";
  Diagnostic e = historyErrorOf(d);
  EXPECT_EQ(e.resource, "resolved_prev");
  EXPECT_NE(e.message.find("no enabled pass writes its source 'never'"), std::string::npos) << e.message;
  EXPECT_EQ(withCode(compile(d), DiagCode::read_never_written).size(), 0u) << "no second error at the reader";
}

TEST(HistoryDiagnostics, SourceWhoseEveryWriterIsDisabled) {
  GraphDesc d = taaGraph();
  d.passes[1].enabled = false;  // taa, the only writer of resolved
  d.passes[2].uses[0].input = "scene";
  d.resources[1].texture.format = Format::rgba16f;
  Diagnostic e = historyErrorOf(d);
  EXPECT_NE(e.message.find("its writers are disabled"), std::string::npos) << e.message;
}

TEST(HistoryDiagnostics, DescriptorMismatchNamesBothDescriptors) {
  struct Case {
    const char* what;
    void (*change)(TextureDesc&);
    const char* expect;
  } cases[] = {
      {"format", [](TextureDesc& t) { t.format = Format::rgba8; }, "(rgba8, output size (1280x720), 1 sample"},
      {"size", [](TextureDesc& t) { t.size = SizeSpec::relative(0.5f); }, "scale 0.5 (640x360)"},
      {"samples", [](TextureDesc& t) { t.samples = 4; }, "4 samples"},
      {"mips", [](TextureDesc& t) { t.mips = 3; }, "3 mip levels"},
  };
  for (const Case& c : cases) {
    GraphDesc d = taaGraph();
    c.change(d.resources[2].texture);
    Diagnostic e = historyErrorOf(d);
    EXPECT_EQ(e.where.column, 5) << "at the history resource";
    EXPECT_NE(e.message.find(c.expect), std::string::npos) << c.what << ": " << e.message;
    EXPECT_NE(e.message.find("its source 'resolved' (rgba16f, output size (1280x720), 1 sample, 1 mip level)"),
              std::string::npos)
        << c.what << ": " << e.message;
  }
}

TEST(HistoryDiagnostics, HistoryOfAnImportedResourceOrTheOutput) {
  GraphDesc d = taaGraph();
  d.resources.push_back(importedTex("caller", true, Format::rgba16f));
  d.resources[2].historyOf = "caller";
  Diagnostic e = historyErrorOf(d);
  EXPECT_NE(e.message.find("imported resource 'caller', whose content the caller owns between frames"),
            std::string::npos)
      << e.message;

  GraphDesc o = taaGraph();
  o.resources[2].historyOf = "out";
  o.resources[2].texture.format = Format::rgba8;
  e = historyErrorOf(o);
  EXPECT_NE(e.message.find("the output image 'out', whose content belongs to the caller (presentation)"),
            std::string::npos)
      << e.message;
}

TEST(HistoryDiagnostics, HistoryOfAHistory) {
  GraphDesc d = taaGraph();
  d.resources.push_back(historyOf("older", "resolved_prev"));
  d.passes[1].uses.push_back(rd("older", "older"));
  Diagnostic e = historyErrorOf(d);
  EXPECT_EQ(e.resource, "older");
  EXPECT_NE(e.message.find("itself a history resource (of 'resolved')"), std::string::npos) << e.message;
}

TEST(HistoryDiagnostics, BuffersKeepNoHistory) {
  GraphDesc d = taaGraph();
  d.resources.push_back(buffer("counts", 256));
  d.passes[0].uses.push_back(wr("counts", "counts", Access::storage_write));
  d.resources[2].historyOf = "counts";
  Diagnostic e = historyErrorOf(d);
  EXPECT_NE(e.message.find("its source 'counts' is a buffer; only textures keep a history"), std::string::npos)
      << e.message;
}

TEST(HistoryDiagnostics, TwoHistoriesOfOneSource) {
  GraphDesc d = taaGraph();
  d.resources.push_back(historyOf("again", "resolved"));
  d.passes[1].uses.push_back(rd("again", "again"));
  Diagnostic e = historyErrorOf(d);
  EXPECT_NE(e.message.find("'resolved' already has the history resource 'resolved_prev'"), std::string::npos)
      << e.message;
}

TEST(HistoryDiagnostics, PassWritingAHistoryResource) {
  GraphDesc d = taaGraph();
  d.passes.push_back(pass("overwrite", {wr("color", "resolved_prev")}, /*sideEffect=*/true));
  d.passes.back().uses[0].outputWhere = at(30, 40, "/passes/3/outputs/color");
  Diagnostic e = historyErrorOf(d);
  EXPECT_EQ(e.pass, "overwrite");
  EXPECT_EQ(e.where.line, 30);
  EXPECT_NE(e.message.find("history resources are written by the executor, not by passes"), std::string::npos)
      << e.message;

  GraphDesc l = taaGraph();  // loading it in place is writing it too
  l.passes.push_back(pass("blend_in", {rmw("color", "resolved_prev", "prev_blended")}, /*sideEffect=*/true));
  e = historyErrorOf(l);
  EXPECT_EQ(e.pass, "blend_in");
}

}  // namespace
