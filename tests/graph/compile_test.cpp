// Behaviour of compile(): versions, ordering, culling, lifetimes, aliasing.
#include <gtest/gtest.h>

#include <algorithm>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;
using Strings = std::vector<std::string>;

namespace {

// gbuffer -> lighting -> tonemap -> out (imported output image).
GraphDesc deferred() {
  GraphDesc d;
  d.resources = {tex("gColor"), tex("gDepth", Format::depth24), tex("hdr", Format::rgba16f),
                 importedTex("out", false)};
  d.passes = {
      pass("gbuffer", {wr("color", "gColor"), wr("depth", "gDepth", Access::depth_attachment)}),
      pass("lighting", {rd("albedo", "gColor"), rd("depth", "gDepth"), wr("color", "hdr")}),
      pass("tonemap", {rd("src", "hdr"), wr("color", "out")}),
  };
  d.output = "out";
  return d;
}

TEST(Compile, LinearGraphOrderLifetimesAndBindings) {
  Plan plan = compile(deferred());
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(plan.output, (Extent{1280, 720}));
  EXPECT_EQ(plan.outputResource, ResourceIndex(3));
  EXPECT_EQ(plan.outputVersion, "out");
  EXPECT_EQ(res(plan, "gColor").firstPass, StepIndex(0));
  EXPECT_EQ(res(plan, "gColor").lastPass, StepIndex(1));
  EXPECT_EQ(res(plan, "gDepth").firstPass, StepIndex(0));
  EXPECT_EQ(res(plan, "gDepth").lastPass, StepIndex(1));
  EXPECT_EQ(res(plan, "hdr").firstPass, StepIndex(1));
  EXPECT_EQ(res(plan, "hdr").lastPass, StepIndex(2));
  EXPECT_EQ(res(plan, "out").firstPass, StepIndex(2));
  EXPECT_EQ(res(plan, "out").lastPass, StepIndex(2));
  EXPECT_FALSE(res(plan, "out").physical.valid());
  EXPECT_EQ(res(plan, "hdr").extent, (Extent{1280, 720}));
  EXPECT_EQ(res(plan, "hdr").bytes, 1280u * 720u * 8u);

  ASSERT_EQ(plan.bindings.size(), 3u);
  ASSERT_EQ(plan.bindings[1].size(), 3u);
  const BoundUse& albedo = plan.bindings[1][0];
  EXPECT_EQ(albedo.slot, "albedo");
  EXPECT_EQ(albedo.access, Access::sampled);
  EXPECT_EQ(albedo.resource, ResourceIndex(0));
  EXPECT_EQ(albedo.readVersion, "gColor");
  EXPECT_TRUE(albedo.writeVersion.empty());
  EXPECT_FALSE(albedo.firstWrite);
  const BoundUse& hdr = plan.bindings[1][2];
  EXPECT_EQ(hdr.resource, ResourceIndex(2));
  EXPECT_EQ(hdr.writeVersion, "hdr");
  EXPECT_TRUE(hdr.readVersion.empty());
  EXPECT_TRUE(hdr.firstWrite);
  for (const auto& p : plan.passes) {
    EXPECT_FALSE(p.culled);
    EXPECT_EQ(p.type, "test");
  }
}

TEST(Compile, OrderRespectsDependenciesWhenDeclaredOutOfOrder) {
  GraphDesc d = deferred();
  std::swap(d.passes[0], d.passes[2]);  // tonemap, lighting, gbuffer
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"gbuffer", "lighting", "tonemap"}));
  // Plan::passes stays in declaration order.
  EXPECT_EQ(plan.passes[0].name, "tonemap");
  EXPECT_EQ(plan.passes[0].decl, PassIndex(0));
  EXPECT_EQ(plan.passes[0].order, StepIndex(2));
  EXPECT_EQ(plan.passes[2].order, StepIndex(0));
  EXPECT_EQ(plan.order, (std::vector<PassIndex>{PassIndex(2), PassIndex(1), PassIndex(0)}));
}

TEST(Compile, TiesKeepDeclarationOrderAndCompileIsDeterministic) {
  GraphDesc d;
  d.resources = {tex("a"), tex("b"), tex("c"), tex("out")};
  d.passes = {
      pass("final", {rd("x", "c"), rd("y", "a"), rd("z", "b"), wr("color", "out")}),
      pass("makeC", {wr("color", "c")}),
      pass("makeA", {wr("color", "a")}),
      pass("makeB", {wr("color", "b")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"makeC", "makeA", "makeB", "final"}));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(compile(d).order, plan.order);
}

TEST(Compile, CullsDebugPassAndTheChainBehindIt) {
  GraphDesc d;
  d.resources = {tex("scene"), tex("dbg_a"), tex("debug_view"), importedTex("out", false)};
  d.passes = {
      pass("render", {wr("color", "scene")}),
      pass("debug_prep", {rd("src", "scene"), wr("color", "dbg_a")}),
      pass("debug", {rd("src", "dbg_a"), wr("color", "debug_view")}),
      pass("present", {rd("src", "scene"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"render", "present"}));
  const PlannedPass& debug = plan.passes[2];
  EXPECT_TRUE(debug.culled);
  EXPECT_FALSE(debug.order.valid());
  EXPECT_NE(debug.reason.find("debug_view"), std::string::npos) << debug.reason;
  EXPECT_NE(debug.reason.find("never read"), std::string::npos) << debug.reason;
  EXPECT_TRUE(plan.passes[1].culled);
  EXPECT_NE(plan.passes[1].reason.find("dbg_a"), std::string::npos);
  EXPECT_FALSE(plan.passes[0].culled);
  // Resources only culled passes touch are unused: no physical, no bytes.
  EXPECT_FALSE(res(plan, "debug_view").physical.valid());
  EXPECT_FALSE(res(plan, "debug_view").firstPass.valid());
  EXPECT_FALSE(res(plan, "dbg_a").physical.valid());
  EXPECT_EQ(plan.naiveBytes, res(plan, "scene").bytes);
  EXPECT_EQ(plan.allocatedBytes, res(plan, "scene").bytes);
  ASSERT_EQ(plan.physical.size(), 1u);
}

TEST(Compile, SideEffectPassIsNotCulledNorAnythingItNeeds) {
  GraphDesc d;
  d.resources = {tex("scene"), tex("lum", Format::r16f), buffer("stats", 256), importedTex("out", false)};
  d.passes = {
      pass("render", {wr("color", "scene")}),
      pass("luminance", {rd("src", "scene"), wr("color", "lum")}),
      pass("readback", {rd("src", "lum"), wr("stats", "stats", Access::storage_write)}, /*sideEffect=*/true),
      pass("present", {rd("src", "scene"), wr("color", "out")}),
      pass("unused", {rd("src", "scene"), wr("color", "lum_unused_never")}, false),
  };
  d.resources.push_back(tex("lum_unused_never"));
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"render", "luminance", "readback", "present"}));
  EXPECT_TRUE(plan.passes[4].culled);
  EXPECT_EQ(res(plan, "stats").firstPass, StepIndex(2));
  EXPECT_TRUE(res(plan, "stats").physical.valid());
}

TEST(Compile, InPlaceVersionsShareOneResourceAndPhysical) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f), importedTex("out", false)};
  d.passes = {
      pass("clear", {wr("color", "hdr")}),
      pass("lights", {rmw("color", "hdr", "hdr_lit")}),
      pass("sky", {rmw("color", "hdr_lit", "hdr_sky")}),
      pass("tonemap", {rd("src", "hdr_sky"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"clear", "lights", "sky", "tonemap"}));
  const PlannedResource& hdr = res(plan, "hdr");
  EXPECT_EQ(hdr.versions, (Strings{"hdr", "hdr_lit", "hdr_sky"}));
  EXPECT_EQ(hdr.firstPass, StepIndex(0));
  EXPECT_EQ(hdr.lastPass, StepIndex(3));
  ASSERT_EQ(plan.physical.size(), 1u);
  EXPECT_EQ(plan.physical[0].resources, (std::vector<ResourceIndex>{ResourceIndex(0)}));
  EXPECT_EQ(plan.physical[0].format, Format::rgba16f);
  const BoundUse& lit = plan.bindings[1][0];
  EXPECT_EQ(lit.resource, ResourceIndex(0));
  EXPECT_EQ(lit.readVersion, "hdr");
  EXPECT_EQ(lit.writeVersion, "hdr_lit");
  EXPECT_FALSE(lit.firstWrite);
  EXPECT_TRUE(plan.bindings[0][0].firstWrite);
  // Naming an intermediate version as the output means that version: the
  // pass producing the later one is culled (tests/graph/output_version_test.cpp).
  d.output = "hdr_lit";
  d.passes.pop_back();
  Plan p2 = compile(d);
  ASSERT_TRUE(p2.ok()) << dumpDiagnostics(p2);
  EXPECT_EQ(p2.outputResource, ResourceIndex(0));
  EXPECT_EQ(p2.outputVersion, "hdr_lit");
  EXPECT_EQ(orderNames(p2), (Strings{"clear", "lights"}));
}

TEST(Compile, WriteAfterReadRunsReaderOfOldVersionFirst) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f), tex("bright", Format::rgba16f), importedTex("out", false)};
  // "blend" overwrites hdr (version 1) and is declared before "extract",
  // which reads version 0: extract must still run before blend.
  d.passes = {
      pass("base", {wr("color", "hdr")}),
      pass("blend", {rmw("color", "hdr", "hdr_blend")}),
      pass("extract", {rd("src", "hdr"), wr("color", "bright")}),
      pass("compose", {rd("a", "hdr_blend"), rd("b", "bright"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"base", "extract", "blend", "compose"}));
  // Aliasing must respect the in-place chain: hdr lives from base to compose.
  EXPECT_EQ(res(plan, "hdr").firstPass, StepIndex(0));
  EXPECT_EQ(res(plan, "hdr").lastPass, StepIndex(3));
  EXPECT_NE(res(plan, "hdr").physical, res(plan, "bright").physical);
}

TEST(Compile, WarEdgeAloneDoesNotKeepAReaderAlive) {
  GraphDesc d;
  d.resources = {tex("hdr"), tex("side"), importedTex("out", false)};
  d.passes = {
      pass("base", {wr("color", "hdr")}),
      pass("peek", {rd("src", "hdr"), wr("color", "side")}),  // nobody reads side
      pass("blend", {rmw("color", "hdr", "hdr2")}),
      pass("present", {rd("src", "hdr2"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"base", "blend", "present"}));
  EXPECT_TRUE(plan.passes[1].culled);
}

TEST(Compile, ImportedResourcesAreReadableAndNeverPooled) {
  GraphDesc d;
  d.resources = {importedTex("env", true, Format::rgba16f), tex("a", Format::rgba16f), tex("b", Format::rgba16f),
                 importedTex("out", false)};
  d.passes = {
      pass("sky", {rd("env", "env"), wr("color", "a")}),
      pass("fx", {rd("src", "a"), wr("color", "b")}),
      pass("present", {rd("src", "b"), rd("env", "env"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"sky", "fx", "present"}));
  const PlannedResource& env = res(plan, "env");
  EXPECT_TRUE(env.imported);
  EXPECT_FALSE(env.physical.valid());
  EXPECT_EQ(env.firstPass, StepIndex(0));
  EXPECT_EQ(env.lastPass, StepIndex(2));
  EXPECT_FALSE(res(plan, "out").physical.valid());
  // Transient a [0,1] and b [1,2] overlap; env never joins a pool even though its descriptor matches.
  ASSERT_EQ(plan.physical.size(), 2u);
  for (const auto& ph : plan.physical)
    for (ResourceIndex r : ph.resources) EXPECT_FALSE(plan.resource(r).imported);
  EXPECT_EQ(plan.naiveBytes, 2u * 1280u * 720u * 8u);
}

TEST(Compile, DisabledInPlacePassIsAPassThrough) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f), importedTex("out", false)};
  d.passes = {
      pass("lighting", {wr("color", "hdr")}),
      pass("bloom", {rmw("color", "hdr", "hdr_bloom")}, false, /*enabled=*/false),
      pass("tonemap", {rd("src", "hdr_bloom"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"lighting", "tonemap"}));
  EXPECT_TRUE(plan.passes[1].culled);
  EXPECT_EQ(plan.passes[1].reason, "disabled");
  EXPECT_FALSE(plan.passes[1].order.valid());
  EXPECT_EQ(res(plan, "hdr").versions, (Strings{"hdr", "hdr_bloom"}));
  EXPECT_EQ(res(plan, "hdr").firstPass, StepIndex(0));
  EXPECT_EQ(res(plan, "hdr").lastPass, StepIndex(1));
  // The tonemap binding still names the version, resolved to the same resource.
  EXPECT_EQ(plan.bindings[2][0].resource, ResourceIndex(0));
  EXPECT_EQ(plan.bindings[2][0].readVersion, "hdr_bloom");
}

TEST(Compile, DisabledPassThroughAtTheEndStillFeedsTheOutput) {
  GraphDesc d;
  d.resources = {importedTex("out", false)};
  d.passes = {
      pass("draw", {wr("color", "out")}),
      pass("overlay", {rmw("color", "out", "out_overlay")}, false, false),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  // The disabled overlay aliases "out": that is the version actually written.
  EXPECT_EQ(plan.outputVersion, "out");
  EXPECT_EQ(plan.outputResource, ResourceIndex(0));
  EXPECT_EQ(orderNames(plan), (Strings{"draw"}));
}

TEST(Compile, PassThroughInTheMiddleKeepsWriteAfterReadOrder) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f), tex("probe"), importedTex("out", false)};
  // fog is disabled, so hdr_fog means hdr; "overwrite" produces the next real
  // version and is declared before the reader of hdr_fog: it must still run after it.
  d.passes = {
      pass("base", {wr("color", "hdr")}),
      pass("fog", {rmw("color", "hdr", "hdr_fog")}, false, false),
      pass("overwrite", {rmw("color", "hdr_fog", "hdr_final")}),
      pass("probe", {rd("src", "hdr_fog"), wr("color", "probe")}),
      pass("present", {rd("a", "hdr_final"), rd("b", "probe"), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"base", "probe", "overwrite", "present"}));
  EXPECT_EQ(res(plan, "hdr").versions, (Strings{"hdr", "hdr_fog", "hdr_final"}));
}

TEST(Compile, LongInPlaceChainOfOneResource) {
  // More version names than the name table initially expects.
  GraphDesc d;
  d.resources = {tex("acc", Format::rgba32f), importedTex("out", false)};
  d.passes.push_back(pass("clear", {wr("color", "acc")}));
  std::string prev = "acc";
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    std::string next = "acc_" + std::to_string(i) + "_with_a_rather_long_version_name";
    d.passes.push_back(pass("add" + std::to_string(i), {rmw("color", prev, next)}));
    prev = next;
  }
  d.passes.push_back(pass("present", {rd("src", prev), wr("color", "out")}));
  std::reverse(d.passes.begin(), d.passes.end());  // declared backwards
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  ASSERT_EQ(plan.order.size(), static_cast<size_t>(n + 2));
  EXPECT_EQ(plan.pass(plan.order.front()).name, "clear");
  EXPECT_EQ(plan.pass(plan.order.back()).name, "present");
  for (int i = 0; i < n; ++i) EXPECT_EQ(orderOf(plan, "add" + std::to_string(i)), i + 1);
  EXPECT_EQ(res(plan, "acc").versions.size(), static_cast<size_t>(n + 1));
  EXPECT_EQ(res(plan, "acc").versions.back(), prev);
  EXPECT_EQ(res(plan, "acc").firstPass, StepIndex(0));
  EXPECT_EQ(res(plan, "acc").lastPass, StepIndex(n + 1));
  EXPECT_EQ(plan.physical.size(), 1u);
}

// p0 -> t0 -> p1 -> t1 -> ... : consecutive lifetimes touch (inclusive), so
// only every other texture may share.
GraphDesc chain(int n, bool sameFormat = true) {
  GraphDesc d;
  for (int i = 0; i < n; ++i) d.resources.push_back(tex("t" + std::to_string(i)));
  d.resources.push_back(importedTex("out", false));
  d.passes.push_back(pass("p0", {wr("color", "t0")}));
  for (int i = 1; i < n; ++i)
    d.passes.push_back(
        pass("p" + std::to_string(i), {rd("src", "t" + std::to_string(i - 1)), wr("color", "t" + std::to_string(i))}));
  d.passes.push_back(pass("present", {rd("src", "t" + std::to_string(n - 1)), wr("color", "out")}));
  d.output = "out";
  return d;
}

TEST(Compile, AliasingSharesExactlyAlternateChainTextures) {
  Plan plan = compile(chain(4));
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(plan.resources[i].firstPass, StepIndex(i));
    EXPECT_EQ(plan.resources[i].lastPass, StepIndex(i + 1));
  }
  ASSERT_EQ(plan.physical.size(), 2u);
  EXPECT_EQ(plan.physical[0].resources, (std::vector<ResourceIndex>{ResourceIndex(0), ResourceIndex(2)}));
  EXPECT_EQ(plan.physical[1].resources, (std::vector<ResourceIndex>{ResourceIndex(1), ResourceIndex(3)}));
  EXPECT_EQ(plan.resources[0].physical, PhysicalIndex(0));
  EXPECT_EQ(plan.resources[1].physical, PhysicalIndex(1));
  EXPECT_EQ(plan.resources[2].physical, PhysicalIndex(0));
  EXPECT_EQ(plan.resources[3].physical, PhysicalIndex(1));
  const uint64_t one = 1280ull * 720ull * 4ull;
  EXPECT_EQ(plan.naiveBytes, 4 * one);
  EXPECT_EQ(plan.allocatedBytes, 2 * one);
  EXPECT_EQ(plan.physical[0].extent, (Extent{1280, 720}));
  EXPECT_EQ(plan.physical[0].bytes, one);
  EXPECT_EQ(plan.peakLiveBytes, 2 * one) << "two textures live at each middle pass: aliasing is optimal here";

  CompileOptions noAlias;
  noAlias.alias = false;
  Plan separate = compile(chain(4), noAlias);
  ASSERT_TRUE(separate.ok());
  EXPECT_EQ(separate.physical.size(), 4u);
  EXPECT_EQ(separate.allocatedBytes, separate.naiveBytes);
}

TEST(Compile, LongChainNeedsExactlyTwoPhysicalTextures) {
  for (int n : {2, 3, 17, 64}) {
    Plan plan = compile(chain(n));
    ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
    EXPECT_EQ(plan.physical.size(), 2u) << n;
    EXPECT_EQ(plan.allocatedBytes, 2ull * 1280 * 720 * 4) << n;
  }
}

TEST(Compile, IncompatibleDescriptorsNeverShare) {
  GraphDesc d;
  d.resources = {
      tex("a"),
      tex("b"),
      tex("c", Format::rgba16f),
      tex("d", Format::rgba8, SizeSpec::relative(0.5f)),
      tex("e", Format::rgba8, SizeSpec::output(), 0),
      tex("f"),
      tex("g", Format::rgba8, SizeSpec::output(), 1, 4),
      importedTex("out", false),
  };
  d.passes = {
      pass("pa", {wr("color", "a")}),
      pass("pb", {rd("s", "a"), wr("color", "b")}),
      pass("pc", {rd("s", "b"), wr("color", "c")}),
      pass("pd", {rd("s", "c"), wr("color", "d")}),
      pass("pe", {rd("s", "d"), wr("color", "e")}),
      pass("pf", {rd("s", "e"), wr("color", "f")}),
      pass("pg", {rd("s", "f"), wr("color", "g")}),
      pass("present", {rd("s", "g", Access::blit_src), wr("color", "out", Access::blit_dst)}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  // Only a [0,1] and f [5,6] match (b [1,2] matches too, but the lowest free physical wins).
  ASSERT_EQ(plan.physical.size(), 6u);
  EXPECT_EQ(plan.physical[0].resources, (std::vector<ResourceIndex>{ResourceIndex(0), ResourceIndex(5)}));
  for (size_t i = 1; i < plan.physical.size(); ++i) EXPECT_EQ(plan.physical[i].resources.size(), 1u) << i;
  EXPECT_EQ(res(plan, "d").extent, (Extent{640, 360}));
  EXPECT_EQ(plan.physicalTexture(res(plan, "e").physical).mips, 11u);  // full chain of 1280x720
  EXPECT_EQ(plan.physicalTexture(res(plan, "g").physical).samples, 4u);
  EXPECT_LT(plan.allocatedBytes, plan.naiveBytes);
  // Two textures are live at each middle pass; the largest pair is c and d,
  // or g (4 samples) and f: what a format-agnostic allocator would need.
  const uint64_t px = 1280ull * 720ull, rgba8 = px * 4;
  const uint64_t bytesG = res(plan, "g").bytes;
  EXPECT_EQ(bytesG, 4 * rgba8);
  EXPECT_EQ(plan.peakLiveBytes, rgba8 + bytesG) << "f and g live at pg";
  EXPECT_LT(plan.peakLiveBytes, plan.allocatedBytes) << "formats and sizes keep the others apart";
}

TEST(Compile, BuffersArePooledBySize) {
  GraphDesc d;
  d.resources = {buffer("b0", 1024), buffer("b1", 1024), buffer("b2", 1024), buffer("big", 4096),
                 importedTex("out", false)};
  Access sw = Access::storage_write, sr = Access::storage_read;
  d.passes = {
      pass("s0", {wr("o", "b0", sw)}),
      pass("s1", {rd("i", "b0", sr), wr("o", "b1", sw)}),
      pass("s2", {rd("i", "b1", sr), wr("o", "b2", sw)}),
      pass("s3", {rd("i", "b2", sr), wr("o", "big", sw)}),
      pass("present", {rd("i", "big", sr), wr("color", "out")}),
  };
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  EXPECT_EQ(res(plan, "b0").physical, res(plan, "b2").physical);
  EXPECT_NE(res(plan, "b0").physical, res(plan, "b1").physical);
  EXPECT_NE(res(plan, "big").physical, res(plan, "b0").physical);
  EXPECT_NE(res(plan, "big").physical, res(plan, "b1").physical);
  EXPECT_EQ(plan.physical.size(), 3u);
  EXPECT_EQ(plan.physicalTexture(res(plan, "big").physical).kind, ResourceKind::buffer);
  EXPECT_EQ(plan.physicalTexture(res(plan, "big").physical).bytes, 4096u);
  EXPECT_EQ(plan.naiveBytes, 3u * 1024u + 4096u);
  EXPECT_EQ(plan.allocatedBytes, 2u * 1024u + 4096u);
}

TEST(Compile, UnusedTransientHasNoPhysicalAndNoBytes) {
  GraphDesc d = deferred();
  d.resources.push_back(tex("spare", Format::rgba32f));
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  const PlannedResource& spare = res(plan, "spare");
  EXPECT_FALSE(spare.physical.valid());
  EXPECT_FALSE(spare.firstPass.valid());
  EXPECT_FALSE(spare.lastPass.valid());
  EXPECT_EQ(spare.bytes, 1280u * 720u * 16u);
  EXPECT_EQ(plan.naiveBytes, res(plan, "gColor").bytes + res(plan, "gDepth").bytes + res(plan, "hdr").bytes);
}

TEST(Compile, OutputExtentOptionResolvesSizes) {
  GraphDesc d = deferred();
  d.resources[2].texture.size = SizeSpec::relative(0.25f);
  d.resources[1].texture.size = SizeSpec::absolute(1280, 720);
  CompileOptions o;
  o.output = {1920, 1080};
  Plan plan = compile(d, o);
  // gDepth (absolute 1280x720) and gColor (1920x1080) are attachments of one pass.
  EXPECT_EQ(withCode(plan, DiagCode::attachment_size_mismatch).size(), 1u);
  EXPECT_EQ(res(plan, "hdr").extent, (Extent{480, 270}));
  EXPECT_EQ(res(plan, "gColor").extent, (Extent{1920, 1080}));
  EXPECT_EQ(plan.output, (Extent{1920, 1080}));
}

TEST(GraphUtil, ResolveSize) {
  Extent out{1280, 720};
  EXPECT_EQ(resolveSize(SizeSpec::output(), out), out);
  EXPECT_EQ(resolveSize(SizeSpec::absolute(64, 32), out), (Extent{64, 32}));
  EXPECT_EQ(resolveSize(SizeSpec::relative(0.5f), out), (Extent{640, 360}));
  EXPECT_EQ(resolveSize(SizeSpec::relative(1.0f / 3.0f), out), (Extent{427, 240}));  // rounds
  EXPECT_EQ(resolveSize(SizeSpec::relative(0.0001f), out), (Extent{1, 1}));        // at least 1
  EXPECT_EQ(resolveSize(SizeSpec::relative(2.0f), {3, 5}), (Extent{6, 10}));
}

TEST(GraphUtil, TextureBytes) {
  EXPECT_EQ(textureBytes(Format::rgba8, {4, 4}, 1, 1), 64u);
  EXPECT_EQ(textureBytes(Format::rgba16f, {4, 4}, 1, 4), 4u * 4u * 8u * 4u);
  // Full chain of 4x4: 16 + 4 + 1 texels.
  EXPECT_EQ(textureBytes(Format::r8, {4, 4}, 0, 1), 21u);
  EXPECT_EQ(textureBytes(Format::r8, {4, 4}, 2, 1), 20u);
  // Non-square: 8x2 -> 4x1 -> 2x1 -> 1x1.
  EXPECT_EQ(textureBytes(Format::r8, {8, 2}, 0, 1), 16u + 4u + 2u + 1u);
  EXPECT_EQ(textureBytes(Format::rgb32f, {2, 2}, 1, 1), 48u);
}

TEST(GraphUtil, AccessKinds) {
  EXPECT_TRUE(isWriteAccess(Access::color_attachment));
  EXPECT_TRUE(isWriteAccess(Access::depth_attachment));
  EXPECT_TRUE(isWriteAccess(Access::storage_write));
  EXPECT_TRUE(isWriteAccess(Access::blit_dst));
  EXPECT_FALSE(isWriteAccess(Access::depth_attachment_read));
  EXPECT_FALSE(isWriteAccess(Access::sampled));
  EXPECT_FALSE(isWriteAccess(Access::storage_read));
  EXPECT_FALSE(isWriteAccess(Access::blit_src));
  EXPECT_TRUE(isAttachmentAccess(Access::depth_attachment_read));
  EXPECT_FALSE(isAttachmentAccess(Access::storage_write));
  EXPECT_EQ(accessName(Access::depth_attachment_read), "depth_attachment_read");
  EXPECT_EQ(accessName(Access::blit_dst), "blit_dst");
}

}  // namespace
