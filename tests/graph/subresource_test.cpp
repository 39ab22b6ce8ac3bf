// Subresources: texture shapes, the "NAME.mip[..].layer[..]" syntax, and
// per-subresource versions, ordering, culling and hazards (mip chains, atlas
// layers, cube faces, layered writes), with lifetimes and aliasing per texture.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;
using Strings = std::vector<std::string>;

namespace {

// A use whose name carries a subresource ("bloom.mip[2]"), split as the config does.
ResourceUse part(ResourceUse u) {
  std::string name;
  Subresource sub;
  std::string& text = isWriteAccess(u.access) ? u.output : u.input;
  EXPECT_EQ(parseSubresourceRef(text, name, sub), "") << text;
  if (isWriteAccess(u.access) && !u.input.empty()) {
    std::string in;
    Subresource inSub;
    EXPECT_EQ(parseSubresourceRef(u.input, in, inSub), "");
    u.input = in;
  }
  text = name;
  u.sub = sub;
  return u;
}
ResourceUse rdp(std::string slot, std::string input) { return part(rd(std::move(slot), std::move(input))); }
ResourceUse wrp(std::string slot, std::string output, Access a = Access::color_attachment) {
  return part(wr(std::move(slot), std::move(output), a));
}
ResourceUse rmwp(std::string slot, std::string input, std::string output) {
  return part(rmw(std::move(slot), std::move(input), std::move(output)));
}

ResourceDecl shaped(std::string name, uint32_t size, uint32_t mips, uint32_t layers = 1, bool cube = false,
                    Format f = Format::rgba16f) {
  ResourceDecl r = tex(std::move(name), f, SizeSpec::absolute(size, size), mips);
  r.texture.layers = layers;
  r.texture.cube = cube;
  return r;
}

std::string messages(const Plan& plan) { return dumpDiagnostics(plan); }

// --------------------------------------------------------------- syntax

TEST(SubresourceSyntax, ParsesMipsLayersFacesAndRanges) {
  std::string name;
  Subresource s;
  EXPECT_EQ(parseSubresourceRef("hdr", name, s), "");
  EXPECT_EQ(name, "hdr");
  EXPECT_TRUE(s.whole());
  EXPECT_EQ(parseSubresourceRef("bloom.mip[2]", name, s), "");
  EXPECT_EQ(name, "bloom");
  EXPECT_EQ(s, (Subresource{2, 1, 0, Subresource::kAll}));
  EXPECT_EQ(parseSubresourceRef("bloom.mip[1..4]", name, s), "");
  EXPECT_EQ(s, (Subresource{1, 4, 0, Subresource::kAll}));
  EXPECT_EQ(parseSubresourceRef("shadow.layer[*]", name, s), "");
  EXPECT_TRUE(s.whole());
  EXPECT_EQ(parseSubresourceRef("env.mip[1].face[-z]", name, s), "");
  EXPECT_EQ(name, "env");
  EXPECT_EQ(s, (Subresource{1, 1, 5, 1}));
  EXPECT_EQ(parseSubresourceRef("env.face[+y]", name, s), "");
  EXPECT_EQ(s, (Subresource{0, Subresource::kAll, 2, 1}));
  // A dot that starts no part is part of the name.
  EXPECT_EQ(parseSubresourceRef("g.buffer", name, s), "");
  EXPECT_EQ(name, "g.buffer");
}

TEST(SubresourceSyntax, RefusesMalformedParts) {
  std::string name;
  Subresource s;
  EXPECT_NE(parseSubresourceRef("bloom.mip[x]", name, s).find("not an index"), std::string::npos);
  EXPECT_NE(parseSubresourceRef("bloom.mip[4..1]", name, s).find("ends before it starts"), std::string::npos);
  EXPECT_NE(parseSubresourceRef("bloom.mip[2", name, s).find("unclosed"), std::string::npos);
  EXPECT_NE(parseSubresourceRef("env.face[+w]", name, s).find("not a cube face"), std::string::npos);
  EXPECT_NE(parseSubresourceRef("bloom.mip[1].mip[2]", name, s).find("twice"), std::string::npos);
  EXPECT_NE(parseSubresourceRef(".mip[1]", name, s).find("no resource name"), std::string::npos);
  EXPECT_NE(parseSubresourceRef("t.mip[1].lod[2]", name, s).find("\"lod\" is not mip, layer or face"),
            std::string::npos);
  EXPECT_NE(parseSubresourceRef("t.mip[1]x", name, s).find("expected .mip[..]"), std::string::npos);
}

TEST(SubresourceSyntax, LabelsRoundTrip) {
  for (const char* text : {"bloom.mip[3]", "shadow.layer[0..3]", "env.face[+x]", "env.mip[2].face[-y]", "hdr",
                           "cubes.layer[7]"}) {
    std::string name;
    Subresource s;
    ASSERT_EQ(parseSubresourceRef(text, name, s), "");
    EXPECT_EQ(subresourceLabel(name, s, std::string(text).find("face") != std::string::npos), text);
  }
}

// --------------------------------------------------------------- shapes

TEST(SubresourceShapes, ArraysAndCubesCountLayersAndBytes) {
  GraphDesc d;
  d.resources = {shaped("atlas", 64, 1, 4), shaped("env", 32, 0, 1, true), shaped("envs", 16, 1, 2, true),
                 tex("out")};
  d.passes = {pass("a", {wr("color", "atlas")}), pass("e", {wr("color", "env")}), pass("es", {wr("color", "envs")}),
              pass("o", {rd("a", "atlas"), rd("e", "env"), rd("s", "envs"), wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(res(plan, "atlas").bytes, 64u * 64u * 8u * 4u);
  EXPECT_EQ(res(plan, "env").bytes, textureBytes(Format::rgba16f, {32, 32}, 0, 1) * 6u);
  EXPECT_EQ(res(plan, "envs").bytes, 16u * 16u * 8u * 12u);
  const PhysicalTexture& env = plan.physicalTexture(res(plan, "env").physical);
  EXPECT_TRUE(env.cube);
  EXPECT_EQ(env.mips, 6u);
  EXPECT_EQ(plan.physicalTexture(res(plan, "atlas").physical).layers, 4u);
  // Whole bindings are resolved to every level and layer.
  EXPECT_EQ(plan.bindings[3][1].sub, (Subresource{0, 6, 0, 6}));
  EXPECT_EQ(plan.bindings[3][2].sub, (Subresource{0, 1, 0, 12}));
}

TEST(SubresourceShapes, RefusesNonSquareCubesZeroLayersAndMultisampledArrays) {
  GraphDesc d;
  ResourceDecl wide = tex("wide", Format::rgba8, SizeSpec::absolute(64, 32));
  wide.texture.cube = true;
  ResourceDecl none = shaped("none", 8, 1, 0);
  ResourceDecl msaa = shaped("msaa", 8, 1, 2);
  msaa.texture.samples = 4;
  ResourceDecl many = shaped("many", 8, 1, 400, true);
  d.resources = {wide, none, msaa, many, tex("out")};
  d.passes = {pass("o", {wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  const std::string m = messages(plan);
  EXPECT_EQ(withCode(plan, DiagCode::invalid_resource).size(), 4u) << m;
  EXPECT_NE(m.find("'wide' is a cube map of 64x32; a cube map's faces are square"), std::string::npos) << m;
  EXPECT_NE(m.find("'none' has 0 layers"), std::string::npos) << m;
  EXPECT_NE(m.find("'msaa' is multisampled (4 samples) and an array"), std::string::npos) << m;
  EXPECT_NE(m.find("400 cubes (2400 array layers), more than the 2048"), std::string::npos) << m;
}

// --------------------------------------------------------------- mip chains

// bright -> mip 0; down k: mip k-1 -> mip k; up k: mip k+1 added into mip k; composite reads mip 0.
GraphDesc mipChain(uint32_t levels) {
  GraphDesc d;
  d.resources = {tex("hdr", Format::rgba16f, SizeSpec::absolute(64, 64)), shaped("bloom", 64, levels),
                 tex("out", Format::rgba8, SizeSpec::absolute(64, 64))};
  d.passes.push_back(pass("bright", {rd("src", "hdr"), wrp("color", "bloom.mip[0]")}));
  for (uint32_t k = 1; k < levels; ++k)
    d.passes.push_back(pass("down" + std::to_string(k), {rdp("src", "bloom.mip[" + std::to_string(k - 1) + "]"),
                                                         wrp("color", "bloom.mip[" + std::to_string(k) + "]")}));
  for (uint32_t k = levels - 1; k-- > 0;) {
    const std::string below = k + 2 == levels ? "bloom" : "bloom_up";
    d.passes.push_back(pass("up" + std::to_string(k),
                            {rdp("src", below + ".mip[" + std::to_string(k + 1) + "]"),
                             rmwp("color", "bloom.mip[" + std::to_string(k) + "]",
                                  "bloom_up.mip[" + std::to_string(k) + "]")}));
  }
  d.passes.push_back(pass("hdr_src", {wr("color", "hdr")}));
  std::rotate(d.passes.begin(), d.passes.end() - 1, d.passes.end());
  d.passes.push_back(pass("composite", {rd("hdr", "hdr"), rdp("bloom", "bloom_up.mip[0]"), wr("color", "out")}));
  d.output = "out";
  return d;
}

TEST(SubresourceGraph, MipChainReadsOneLevelWhileWritingTheNext) {
  const Plan plan = compile(mipChain(4));
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"hdr_src", "bright", "down1", "down2", "down3", "up2", "up1", "up0",
                                       "composite"}));
  // One texture, one lifetime from the first level's writer to the last reader.
  const PlannedResource& bloom = res(plan, "bloom");
  EXPECT_EQ(bloom.firstPass, StepIndex(1));
  EXPECT_EQ(bloom.lastPass, StepIndex(8));
  ASSERT_TRUE(bloom.physical.valid());
  EXPECT_EQ(plan.physicalTexture(bloom.physical).mips, 4u);
  EXPECT_EQ(plan.physicalTexture(bloom.physical).resources, (std::vector<ResourceIndex>{ResourceIndex(1)}));
  // Versions name their subresource.
  EXPECT_NE(std::find(bloom.versions.begin(), bloom.versions.end(), "bloom_up.mip[2]"), bloom.versions.end());
  // Bindings keep the config's names and carry the resolved range.
  const int down2 = passIndex(plan, "down2");
  const BoundUse& src = plan.bindings[down2][0];
  EXPECT_EQ(src.readVersion, "bloom");
  EXPECT_EQ(src.resource, ResourceIndex(1));
  EXPECT_EQ(src.sub, (Subresource{1, 1, 0, 1}));
  EXPECT_EQ(plan.bindings[down2][1].sub, (Subresource{2, 1, 0, 1}));
  EXPECT_TRUE(plan.bindings[down2][1].firstWrite);
  const BoundUse& up = plan.bindings[passIndex(plan, "up1")][1];
  EXPECT_EQ(up.readVersion, "bloom");
  EXPECT_EQ(up.writeVersion, "bloom_up");
  EXPECT_FALSE(up.firstWrite);
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(SubresourceGraph, UnreadLevelsCullTheirWriters) {
  GraphDesc d = mipChain(4);
  // The composite reads level 1's downsample only: levels 2-3 and every up pass feed nothing.
  d.passes.back().uses[1] = rdp("bloom", "bloom.mip[1]");
  const Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"hdr_src", "bright", "down1", "composite"}));
  EXPECT_NE(plan.passes[passIndex(plan, "down3")].reason.find("bloom.mip[3]"), std::string::npos)
      << plan.passes[passIndex(plan, "down3")].reason;
}

TEST(SubresourceGraph, AttachmentSizesAreTheLevelsSizes) {
  GraphDesc d;
  d.resources = {shaped("bloom", 64, 3), tex("depth32", Format::depth24, SizeSpec::absolute(32, 32)),
                 tex("depth64", Format::depth24, SizeSpec::absolute(64, 64))};
  d.passes = {pass("ok", {wrp("color", "bloom.mip[1]"), wr("depth", "depth32", Access::depth_attachment)}, true),
              pass("bad", {wrp("color", "bloom.mip[2]"), wr("depth", "depth64", Access::depth_attachment)}, true)};
  d.output = "bloom";
  const Plan plan = compile(d);
  const auto sizes = withCode(plan, DiagCode::attachment_size_mismatch);
  ASSERT_EQ(sizes.size(), 1u) << messages(plan);
  EXPECT_EQ(sizes[0]->pass, "bad");
  EXPECT_NE(sizes[0]->message.find("is 16x16"), std::string::npos) << sizes[0]->message;
}

TEST(SubresourceGraph, FeedbackLoopsArePerSubresource) {
  GraphDesc d;
  d.resources = {shaped("t", 64, 3)};
  d.passes = {pass("w0", {wrp("color", "t.mip[0]")}),
              pass("next", {rdp("src", "t.mip[0]"), wrp("color", "t.mip[1]")}, true),
              pass("self", {rdp("src", "t.mip[1]"), rmwp("color", "t.mip[1]", "t2.mip[1]")}, true)};
  d.output = "t";
  const Plan plan = compile(d);
  const auto loops = withCode(plan, DiagCode::feedback_loop);
  ASSERT_EQ(loops.size(), 1u) << messages(plan);
  EXPECT_EQ(loops[0]->pass, "self");
}

// --------------------------------------------------------------- layers and faces

// Four shadow passes, one per layer of an atlas, and a reader of `readRef`.
GraphDesc atlas(const std::string& readRef) {
  GraphDesc d;
  d.resources = {shaped("shadow", 64, 1, 4, false, Format::depth32f), tex("out")};
  for (int k = 0; k < 4; ++k)
    d.passes.push_back(pass("s" + std::to_string(k),
                            {wrp("depth", "shadow.layer[" + std::to_string(k) + "]", Access::depth_attachment)}));
  d.passes.push_back(pass("light", {rdp("shadow", readRef), wr("color", "out")}));
  d.output = "out";
  return d;
}

TEST(SubresourceGraph, ReadingAWholeAtlasWaitsForEveryLayer) {
  const Plan plan = compile(atlas("shadow"));
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"s0", "s1", "s2", "s3", "light"}));
}

TEST(SubresourceGraph, ReadingOneLayerKeepsOnlyItsWriter) {
  const Plan plan = compile(atlas("shadow.layer[2]"));
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"s2", "light"}));
  const Plan range = compile(atlas("shadow.layer[1..2]"));
  EXPECT_EQ(orderNames(range), (Strings{"s1", "s2", "light"}));
}

TEST(SubresourceGraph, TwoUnorderedWritersOfOneLayerAreRefused) {
  GraphDesc d = atlas("shadow");
  d.passes.insert(d.passes.begin() + 4, pass("again", {wrp("depth", "shadow.layer[3]", Access::depth_attachment)}));
  const Plan plan = compile(d);
  const auto dup = withCode(plan, DiagCode::duplicate_writer);
  ASSERT_EQ(dup.size(), 1u) << messages(plan);
  EXPECT_EQ(dup[0]->pass, "again");
  EXPECT_NE(dup[0]->message.find("'shadow.layer[3]', which pass 's3' already writes"), std::string::npos)
      << dup[0]->message;
}

TEST(SubresourceGraph, AWholeWriteAndAPartWriteOverlap) {
  GraphDesc d = atlas("shadow");
  d.passes.insert(d.passes.begin(), pass("all", {wr("depth", "shadow", Access::depth_attachment)}));
  const Plan plan = compile(d);
  EXPECT_EQ(withCode(plan, DiagCode::duplicate_writer).size(), 4u) << messages(plan);
}

TEST(SubresourceGraph, LayeredWriteFeedsReadersOfSingleLayers) {
  GraphDesc d;
  d.resources = {shaped("shadow", 64, 1, 4, false, Format::depth32f), tex("out")};
  d.passes = {pass("layered", {wrp("depth", "shadow.layer[*]", Access::depth_attachment)}),
              pass("a", {rdp("s", "shadow.layer[3]"), wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(orderNames(plan), (Strings{"layered", "a"}));
  EXPECT_EQ(plan.bindings[0][0].sub, (Subresource{0, 1, 0, 4}));
  EXPECT_EQ(plan.bindings[1][0].sub, (Subresource{0, 1, 3, 1}));
}

TEST(SubresourceGraph, WriteAfterReadOrdersOnlyTheSameSubresource) {
  GraphDesc d;
  d.resources = {shaped("t", 64, 1, 3), tex("out")};
  d.passes = {pass("w", {wr("color", "t")}),
              // Declared first, must run after "r1" (it overwrites the layer r1 reads).
              pass("over1", {rmwp("color", "t.layer[1]", "t2.layer[1]")}, true),
              pass("over2", {rmwp("color", "t.layer[2]", "t2.layer[2]")}, true),
              pass("r1", {rdp("s", "t.layer[1]"), wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_LT(orderOf(plan, "r1"), orderOf(plan, "over1"));
  EXPECT_LT(orderOf(plan, "over2"), orderOf(plan, "r1"));  // no edge: declaration order
}

TEST(SubresourceGraph, CubeFacesAreNamedAsFaces) {
  GraphDesc d;
  d.resources = {shaped("env", 32, 1, 1, true), tex("out")};
  const char* faces[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (const char* f : faces)
    d.passes.push_back(pass(std::string("f") + f, {wrp("color", std::string("env.face[") + f + "]")}));
  d.passes.push_back(pass("dup", {wrp("color", "env.face[-z]")}));
  d.passes.push_back(pass("sky", {rd("env", "env"), wr("color", "out")}));
  d.output = "out";
  const Plan plan = compile(d);
  const auto dup = withCode(plan, DiagCode::duplicate_writer);
  ASSERT_EQ(dup.size(), 1u) << messages(plan);
  EXPECT_NE(dup[0]->message.find("'env.face[-z]'"), std::string::npos) << dup[0]->message;
  d.passes.erase(d.passes.end() - 2);
  const Plan ok = compile(d);
  ASSERT_TRUE(ok.ok()) << messages(ok);
  EXPECT_EQ(ok.order.size(), 7u);
}

// --------------------------------------------------------------- ranges

TEST(SubresourceGraph, OutOfRangeIndicesNameTheTextureAndItsRange) {
  GraphDesc d;
  d.resources = {shaped("bloom", 16, 5), shaped("atlas", 16, 1, 4), shaped("flat", 16, 1), buffer("buf", 64),
                 tex("out")};
  SourceLocation where = at(12, 30, "/passes/0/inputs/src");
  ResourceUse mip9 = rdp("src", "bloom.mip[9]");
  mip9.inputWhere = where;
  d.passes = {pass("p", {mip9, rdp("a", "atlas.layer[2..4]"), rdp("f", "flat.face[+y]"), rdp("b", "buf.mip[0]"),
                         wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  const auto bad = withCode(plan, DiagCode::subresource_range);
  ASSERT_EQ(bad.size(), 4u) << messages(plan);
  EXPECT_EQ(bad[0]->message,
            "slot 'src' binds 'bloom.mip[9]', but 'bloom' has 5 mip levels (mip[0..4]): mip[9] is out of range");
  EXPECT_EQ(bad[0]->where.line, 12);
  EXPECT_EQ(bad[0]->where.column, 30);
  EXPECT_EQ(bad[0]->pass, "p");
  EXPECT_NE(bad[1]->message.find("'atlas' has 4 array layers (layer[0..3]): layer[4] is out of range"),
            std::string::npos);
  EXPECT_NE(bad[2]->message.find("'flat' has 1 array layer (layer[0]): layer[2] is out of range"), std::string::npos);
  EXPECT_NE(bad[3]->message.find("a part of buffer 'buf'"), std::string::npos);
}

TEST(SubresourceGraph, FullMipChainsResolveAgainstTheSize) {
  GraphDesc d;
  d.resources = {tex("t", Format::rgba8, SizeSpec::relative(0.5f), 0), tex("out")};
  d.passes = {pass("w", {wrp("color", "t.mip[9]")}), pass("r", {rdp("s", "t.mip[9]"), wr("color", "out")})};
  d.output = "out";
  CompileOptions small;
  small.output = {512, 512};  // t is 256x256: 9 levels, mip[0..8]
  EXPECT_EQ(withCode(compile(d, small), DiagCode::subresource_range).size(), 2u);
  CompileOptions large;
  large.output = {1024, 1024};  // 512x512: 10 levels
  EXPECT_TRUE(compile(d, large).ok()) << messages(compile(d, large));
}

}  // namespace

namespace {

// Only textures of one shape share memory: an array never aliases a 2D
// texture, nor a cube an array of six layers.
TEST(SubresourceShapes, AliasingKeepsShapesApart) {
  GraphDesc d;
  d.resources = {shaped("flat", 32, 1), shaped("arr", 32, 1, 6), shaped("cube", 32, 1, 1, true),
                 shaped("flat2", 32, 1), tex("out")};
  d.passes = {pass("a", {wr("color", "flat")}), pass("b", {rd("s", "flat"), wr("color", "arr")}),
              pass("c", {rd("s", "arr"), wr("color", "cube")}), pass("d", {rd("s", "cube"), wr("color", "flat2")}),
              pass("o", {rd("s", "flat2"), wr("color", "out")})};
  d.output = "out";
  const Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << messages(plan);
  EXPECT_EQ(plan.physical.size(), 4u);  // flat and flat2 share; arr, cube and out each their own
  EXPECT_EQ(res(plan, "flat").physical, res(plan, "flat2").physical);
  EXPECT_NE(res(plan, "arr").physical, res(plan, "cube").physical);
}

}  // namespace
