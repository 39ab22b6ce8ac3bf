// Imported resources (the caller's textures, rgraph/renderer.h): never
// aliased, and what a pass writes into one is seen by the caller, so such a
// pass is never culled, nor anything it reads.
#include <gtest/gtest.h>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;
using Strings = std::vector<std::string>;

namespace {

// scene -> present -> out; scene -> picture (-> the caller's inset texture);
// scene -> debug (-> a transient nobody reads).
GraphDesc withCallerTexture(bool insetImported) {
  GraphDesc d;
  d.resources = {tex("scene"), tex("blurred"), importedTex("out", false), tex("debugView")};
  ResourceDecl inset = insetImported ? importedTex("inset", true) : tex("inset");
  d.resources.push_back(inset);
  d.passes = {
      pass("render", {wr("color", "scene")}),
      pass("blur", {rd("src", "scene"), wr("color", "blurred")}),
      pass("picture", {rd("src", "blurred"), wr("color", "inset")}),
      pass("debug", {rd("src", "scene"), wr("color", "debugView")}),
      pass("present", {rd("src", "scene"), wr("color", "out")}),
  };
  d.output = "out";
  return d;
}

TEST(Imported, WriterOfAnImportedResourceIsNotCulledNorWhatItReads) {
  Plan plan = compile(withCallerTexture(true));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"render", "blur", "picture", "present"}));
  EXPECT_FALSE(plan.passes[2].culled);
  EXPECT_TRUE(plan.passes[3].culled) << "a transient nobody reads is still culled";
  EXPECT_TRUE(res(plan, "inset").imported);
  EXPECT_FALSE(res(plan, "inset").physical.valid()) << "imported: never given a (shared) physical texture";
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(Imported, TheSameWriterIsCulledWhenItsTargetIsTheGraphsOwn) {
  Plan plan = compile(withCallerTexture(false));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"render", "present"}));
  EXPECT_TRUE(plan.passes[2].culled);
}

TEST(Imported, ImportedResourceIsNeverAliasedEvenWithDisjointLifetimes) {
  GraphDesc d;
  d.resources = {tex("a"), importedTex("caller", true), tex("b"), importedTex("out", false)};
  d.passes = {
      pass("p1", {wr("color", "a")}),
      pass("p2", {rd("src", "a"), wr("color", "caller")}),
      pass("p3", {wr("color", "b")}),
      pass("p4", {rd("src", "b"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"p1", "p2", "p3", "p4"}));
  EXPECT_EQ(res(plan, "a").physical, res(plan, "b").physical) << "transients with disjoint lifetimes share";
  EXPECT_FALSE(res(plan, "caller").physical.valid());
}

}  // namespace
