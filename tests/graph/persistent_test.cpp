// Persistent resources (ResourceDecl::persistent): content kept across frames
// (the IBL maps), so never aliased, owning a texture for the whole frame; a
// plain transient of the same description in their place is aliased.
#include <gtest/gtest.h>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

// bake writes a (persistent or not); use reads it into b; late writes c, of
// a's description, after a's last read: c may take a's texture unless a persists.
GraphDesc bakeGraph(bool persistent) {
  GraphDesc d;
  ResourceDecl a = tex("a", Format::rgba16f);
  a.persistent = persistent;
  d.resources = {a, tex("b", Format::rgba16f), tex("c", Format::rgba16f), importedTex("out", false)};
  d.passes = {
      pass("bake", {wr("color", "a")}),
      pass("use", {rd("src", "a"), wr("color", "b")}),
      pass("late", {rd("src", "b"), wr("color", "c")}),
      pass("present", {rd("src", "c"), wr("color", "out")}),
  };
  d.output = "out";
  return d;
}

TEST(Persistent, NeverAliasedAndLiveTheWholeFrame) {
  const Plan plain = compile(bakeGraph(false));
  ASSERT_TRUE(plain.ok()) << dumpDiagnostics(plain);
  EXPECT_FALSE(res(plain, "a").persistent);
  EXPECT_EQ(res(plain, "a").physical, res(plain, "c").physical) << "the transient case aliases a and c";

  const Plan kept = compile(bakeGraph(true));
  ASSERT_TRUE(kept.ok()) << dumpDiagnostics(kept);
  EXPECT_TRUE(res(kept, "a").persistent);
  EXPECT_NE(res(kept, "a").physical, res(kept, "c").physical);
  EXPECT_EQ(res(kept, "a").firstPass, StepIndex(0));
  EXPECT_EQ(res(kept, "a").lastPass, StepIndex(static_cast<uint32_t>(kept.order.size() - 1)));
  EXPECT_EQ(kept.physicalTexture(res(kept, "a").physical).resources.size(), 1u);
}

}  // namespace
