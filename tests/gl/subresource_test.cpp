// Textures of every shape in the executor, drawn into and sampled one level
// or layer at a time through the framebuffer cache (PassContext::framebuffer,
// PassContext::texture(slot, sub)): what lands in layer k / level m equals a
// render of the same draw into a plain 2D texture of that level's size, and
// nothing else of the texture changes.
#include <GL/glcorearb.h>

#include <cstdlib>

#include "gl_test_util.h"
#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/framebuffer_cache.h"
#include "rgraph/gl/format.h"
#include "rgraph/pass_decl.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

uint32_t layerParam(const ParamSet& p) {
  const int64_t layer = p.getInt("layer", -1);
  return layer < 0 ? AttachmentRef::kAllLayers : static_cast<uint32_t>(layer);
}

std::vector<ParamDecl> probeParams() {
  using namespace rgraph::decl;
  return {ranged("mip", ParamType::integer, int64_t{0}, 0.0, 15.0, "level drawn into or read"),
          ranged("layer", ParamType::integer, int64_t{-1}, -1.0, 63.0, "layer (-1: all)"),
          ranged("value", ParamType::integer, int64_t{0}, 0.0, 255.0, "blue channel")};
}

// Draws subresource_probe.frag (u_value = "value") into level "mip", layer
// "layer" of its 'color' slot through a framebuffer it asks the cache for.
class DrawInto final : public PassInstance {
  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    gl::bindPassFramebuffer(ctx, {{"color", static_cast<uint32_t>(p.getInt("mip", 0)), layerParam(p)}});
    gl::useProgram(ctx, ctx.program(0));
    glProgramUniform1i(ctx.program(0), glGetUniformLocation(ctx.program(0), "u_value"),
                       static_cast<GLint>(p.getInt("value", 0)));
    gl::bindVertexArray(ctx, ctx.emptyVertexArray());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
};

// Copies level "mip", layer "layer" of its 'src' slot (sampled through
// ctx.texture(slot, sub)) into its 'color' target texel for texel.
class CopyFrom final : public PassInstance {
  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const uint32_t layer = layerParam(p);
    Subresource sub{static_cast<uint32_t>(p.getInt("mip", 0)), 1, layer == AttachmentRef::kAllLayers ? 0 : layer,
                    layer == AttachmentRef::kAllLayers ? Subresource::kAll : 1};
    glBindTextureUnit(0, ctx.texture("src", sub));
    gl::bindPassFramebuffer(ctx);
    gl::useProgram(ctx, ctx.program(0));
    gl::bindVertexArray(ctx, ctx.emptyVertexArray());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
};

PassRegistry probeRegistry() {
  PassRegistry reg = PassRegistry::builtins();
  PassTypeDesc draw;
  draw.name = "draw_into";
  draw.description = "test: draws into one level and layer of 'color'";
  draw.slots = {decl::slot("color", Access::color_attachment, true, SlotDecl::Load::optional, "target")};
  draw.params = probeParams();
  draw.programs = gl::fullscreenPrograms("subresource_probe.frag", {});
  draw.create = [] { return std::make_unique<DrawInto>(); };
  EXPECT_TRUE(reg.add(draw));
  PassTypeDesc copy;
  copy.name = "copy_from";
  copy.description = "test: copies one level and layer of 'src'";
  copy.slots = {decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "source"),
                decl::slot("color", Access::color_attachment, true, SlotDecl::Load::never, "target")};
  copy.params = probeParams();
  ShaderProgramSpec spec = gl::fullscreenProgram("subresource_copy.frag");
  spec.ownSamplers = {"u_src"};
  copy.programs = [spec](const ParamSet&) { return std::vector<ShaderProgramSpec>{spec}; };
  copy.create = [] { return std::make_unique<CopyFrom>(); };
  EXPECT_TRUE(reg.add(copy));
  return reg;
}

ResourceDecl shaped(const std::string& name, Extent e, uint32_t layers, bool cube, uint32_t mips) {
  ResourceDecl r;
  r.name = name;
  r.texture.format = Format::rgba8;
  r.texture.size = SizeSpec::absolute(e.width, e.height);
  r.texture.layers = layers;
  r.texture.cube = cube;
  r.texture.mips = mips;
  r.texture.clear = std::vector<float>{0, 0, 0, 0};
  return r;
}

// Level `level`, layer `layer` of an RGBA8 texture (any target), bottom row first.
std::vector<uint8_t> readLayer(uint32_t texture, uint32_t level, uint32_t layer, Extent e) {
  std::vector<uint8_t> data(size_t{e.width} * e.height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(texture, static_cast<GLint>(level), 0, 0, static_cast<GLint>(layer),
                       static_cast<GLsizei>(e.width), static_cast<GLsizei>(e.height), 1, GL_RGBA, GL_UNSIGNED_BYTE,
                       static_cast<GLsizei>(data.size()), data.data());
  return data;
}

bool allZero(const std::vector<uint8_t>& v) {
  return std::all_of(v.begin(), v.end(), [](uint8_t b) { return b == 0; });
}

// Draws value 7 into level `mip`, layer `layer` of `shape` (layers counted
// as GL counts them: 6 per cube) and into a plain 2D texture of that level's
// size; returns the executor for the caller's readbacks.
struct Drawn {
  std::unique_ptr<Executor> exec;
  Extent level;
};

class SubresourceTest : public GlTest {
 protected:
  PassRegistry reg = probeRegistry();

  Drawn drawInto(ResourceDecl shape, uint32_t mip, uint32_t layer) {
    const Extent base{shape.texture.size.width, shape.texture.size.height};
    const Extent level{std::max(1u, base.width >> mip), std::max(1u, base.height >> mip)};
    GraphBuilder g;
    g.config().graph.resources.push_back(std::move(shape));
    g.texture("flat", Format::rgba8, SizeSpec::absolute(level.width, level.height)).output("out");
    // A full chain: never the shape of "tex", which the graph would otherwise
    // alias with it (its lifetime ends where flat's begins).
    g.config().graph.resources[g.config().graph.resources.size() - 2].texture.mips = 0;
    auto at = [](uint32_t m, uint32_t l, int v) {
      return params({{"mip", int64_t(m)}, {"layer", l == AttachmentRef::kAllLayers ? int64_t{-1} : int64_t(l)},
                     {"value", int64_t(v)}});
    };
    g.pass("into_layer", "draw_into", {writeUse("color", Access::color_attachment, "tex")}, at(mip, layer, 7), true);
    g.pass("into_flat", "draw_into", {writeUse("color", Access::color_attachment, "flat")},
           at(0, AttachmentRef::kAllLayers, 7), true);
    g.pass("out", "draw_into", {writeUse("color", Access::color_attachment, "out")}, at(0, AttachmentRef::kAllLayers, 1));
    auto exec = std::make_unique<Executor>(g.config(), reg, *shaders);
    exec->resize({8, 8});
    exec->renderFrame();
    return {std::move(exec), level};
  }

  // The drawn level/layer equals the 2D render (and holds value 7), every
  // other layer of level 0 and of the drawn level is still cleared.
  void expectOnly(const Drawn& d, uint32_t mip, uint32_t layer, uint32_t layers, Extent base) {
    const uint32_t tex = d.exec->textureOf("tex");
    ASSERT_NE(tex, d.exec->textureOf("flat"));
    const std::vector<uint8_t> got = readLayer(tex, mip, layer, d.level);
    const std::vector<uint8_t> want = readLayer(d.exec->textureOf("flat"), 0, 0, d.level);
    EXPECT_EQ(got, want) << "level " << mip << " layer " << layer;
    ASSERT_GE(got.size(), 8u);
    EXPECT_EQ(got[2], 7) << "blue of the first texel";
    EXPECT_EQ(got[4], 4) << "red of the second texel (4x)";
    for (uint32_t l = 0; l < layers; ++l) {
      if (l != layer || mip != 0) EXPECT_TRUE(allZero(readLayer(tex, 0, l, base))) << "level 0, layer " << l;
      if (l != layer && mip != 0) EXPECT_TRUE(allZero(readLayer(tex, mip, l, d.level))) << "level " << mip << ", layer " << l;
    }
  }
};

}  // namespace

TEST(FramebufferStatus, NamesTheStatusAndListsTheAttachments) {
  EXPECT_EQ(gl::framebufferStatusName(GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT), "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT");
  EXPECT_EQ(gl::framebufferStatusName(GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS),
            "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS");
  EXPECT_EQ(gl::framebufferStatusName(0x8cd5), "GL_FRAMEBUFFER_COMPLETE");
  EXPECT_EQ(gl::framebufferStatusName(0x1234), "unknown status 0x1234");
  gl::FramebufferAttachment color;
  color.slot = "color";
  color.format = Format::rgba16f;
  color.extent = {32, 16};
  color.level = 1;
  color.layer = 3;
  gl::FramebufferAttachment depth;
  depth.slot = "depth";
  depth.format = Format::depth24;
  depth.extent = {64, 32};
  depth.samples = 4;
  const std::vector<gl::FramebufferAttachment> atts{color, depth};
  EXPECT_EQ(gl::framebufferStatusMessage(GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE, atts),
            "framebuffer incomplete: GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE (attachments: color=rgba16f 32x16 level 1 "
            "layer 3, depth=depth24 64x32 x4)");
}

TEST_F(GlTest, IncompleteFramebufferNamesItsStatus) {
  gl::Texture depth = gl::createTexture2D(Format::depth24, {4, 4});
  gl::FramebufferAttachment a;
  a.point = GL_COLOR_ATTACHMENT0;  // a depth image where colour goes: attachment-incomplete
  a.texture = depth.id();
  a.slot = "src";
  a.format = Format::depth24;
  a.extent = {4, 4};
  gl::FramebufferCache cache;
  const unsigned draw = GL_COLOR_ATTACHMENT0;
  try {
    cache.get(std::span(&a, 1), std::span(&draw, 1), "pass 'p'");
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(),
                 "pass 'p': framebuffer incomplete: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT (attachments: src=depth24 4x4)");
  }
  EXPECT_EQ(cache.framebuffers(), 0u) << "an incomplete framebuffer is not kept";
}

TEST_F(GlTest, FramebufferCacheGivesOneFramebufferPerAttachmentSet) {
  gl::Texture t = gl::createTexture2D(Format::rgba8, {8, 8}, 0);
  gl::FramebufferCache cache;
  gl::FramebufferAttachment a;
  a.point = GL_COLOR_ATTACHMENT0;
  a.texture = t.id();
  const unsigned draw = GL_COLOR_ATTACHMENT0;
  const uint32_t level0 = cache.get(std::span(&a, 1), std::span(&draw, 1), "test");
  EXPECT_EQ(cache.get(std::span(&a, 1), std::span(&draw, 1), "test"), level0);
  a.level = 2;
  const uint32_t level2 = cache.get(std::span(&a, 1), std::span(&draw, 1), "test");
  EXPECT_NE(level2, level0);
  EXPECT_EQ(cache.get(std::span(&a, 1), {}, "test") == level2, false) << "draw buffers are part of the key";
  GLint attached = -1;
  glGetNamedFramebufferAttachmentParameteriv(level2, GL_COLOR_ATTACHMENT0, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL,
                                             &attached);
  EXPECT_EQ(attached, 2);
  EXPECT_EQ(cache.framebuffers(), 3u);
  cache.clear();
  EXPECT_EQ(cache.framebuffers(), 0u);
}

TEST_F(SubresourceTest, MipLevelOfA2DTexture) {
  const Drawn d = drawInto(shaped("tex", {16, 8}, 1, false, 3), 2, AttachmentRef::kAllLayers);
  expectOnly(d, 2, 0, 1, {16, 8});
  EXPECT_EQ(d.level, (Extent{4, 2}));
}

TEST_F(SubresourceTest, LayerOfA2DArray) {
  const Drawn d = drawInto(shaped("tex", {16, 8}, 4, false, 1), 0, 2);
  expectOnly(d, 0, 2, 4, {16, 8});
  GLint target = 0;
  glGetTextureParameteriv(d.exec->textureOf("tex"), GL_TEXTURE_TARGET, &target);
  EXPECT_EQ(target, GL_TEXTURE_2D_ARRAY);
}

TEST_F(SubresourceTest, LevelAndLayerOfA2DArray) {
  const Drawn d = drawInto(shaped("tex", {16, 8}, 3, false, 2), 1, 1);
  expectOnly(d, 1, 1, 3, {16, 8});
}

TEST_F(SubresourceTest, FaceOfACubeMap) {
  const Drawn d = drawInto(shaped("tex", {8, 8}, 1, true, 2), 1, 4);  // +z, level 1
  expectOnly(d, 1, 4, 6, {8, 8});
  GLint target = 0;
  glGetTextureParameteriv(d.exec->textureOf("tex"), GL_TEXTURE_TARGET, &target);
  EXPECT_EQ(target, GL_TEXTURE_CUBE_MAP);
}

TEST_F(SubresourceTest, FaceOfACubeArray) {
  const Drawn d = drawInto(shaped("tex", {8, 8}, 2, true, 1), 0, 9);  // cube 1, face -y
  expectOnly(d, 0, 9, 12, {8, 8});
  GLint target = 0;
  glGetTextureParameteriv(d.exec->textureOf("tex"), GL_TEXTURE_TARGET, &target);
  EXPECT_EQ(target, GL_TEXTURE_CUBE_MAP_ARRAY);
}

TEST_F(SubresourceTest, LayerOutsideTheTextureIsRefused) {
  try {
    drawInto(shaped("tex", {8, 8}, 2, false, 1), 0, 2);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("pass 'into_layer' (type 'draw_into'): slot 'color' binds 2 layers; asked "
                                         "for layer 2"),
              std::string::npos)
        << e.what();
  }
}

// Sampling one level or layer (PassContext::texture(slot, sub)) in both
// ways the executor can (views, base/max level): the copy equals the level.
class SampledSubresource : public SubresourceTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(SampledSubresource, CopyOfALevelOrLayerIsExact) {
  setenv("RGRAPH_SUBRESOURCE_SAMPLING", GetParam(), 1);
  struct Case {
    uint32_t layers, mips, mip, layer;
  };
  for (const Case c : {Case{1, 3, 2, AttachmentRef::kAllLayers}, Case{3, 2, 1, 1}, Case{4, 1, 0, 3}}) {
    SCOPED_TRACE("layers " + std::to_string(c.layers) + ", level " + std::to_string(c.mip));
    const Extent level{16u >> c.mip, 8u >> c.mip};
    GraphBuilder g;
    g.config().graph.resources.push_back(shaped("tex", {16, 8}, c.layers, false, c.mips));
    g.texture("copy", Format::rgba8, SizeSpec::absolute(level.width, level.height));
    g.texture("flat", Format::rgba8, SizeSpec::absolute(level.width, level.height)).output("out");
    // A full chain: never the shape of "tex", which the graph would otherwise
    // alias with it (its lifetime ends where flat's begins).
    g.config().graph.resources[g.config().graph.resources.size() - 2].texture.mips = 0;
    auto at = [](uint32_t m, uint32_t l, int v) {
      return params({{"mip", int64_t(m)}, {"layer", l == AttachmentRef::kAllLayers ? int64_t{-1} : int64_t(l)},
                     {"value", int64_t(v)}});
    };
    const uint32_t l = c.layers > 1 ? c.layer : AttachmentRef::kAllLayers;
    g.pass("draw", "draw_into", {writeUse("color", Access::color_attachment, "tex")}, at(c.mip, l, 9));
    g.pass("copy", "copy_from", {readUse("src", Access::sampled, "tex"), writeUse("color", Access::color_attachment, "copy")},
           at(c.mip, l, 0), true);
    g.pass("flat", "draw_into", {writeUse("color", Access::color_attachment, "flat")}, at(0, AttachmentRef::kAllLayers, 9),
           true);
    g.pass("out", "draw_into", {writeUse("color", Access::color_attachment, "out")}, at(0, AttachmentRef::kAllLayers, 1));
    Executor exec(g.config(), reg, *shaders);
    exec.resize({8, 8});
    exec.renderFrame();
    ASSERT_NE(exec.textureOf("copy"), exec.textureOf("flat"));
    const std::vector<uint8_t> got = readLayer(exec.textureOf("copy"), 0, 0, level);
    EXPECT_EQ(got, readLayer(exec.textureOf("flat"), 0, 0, level));
    EXPECT_EQ(got[2], 9);
    GLint base = -1;
    glGetTextureParameteriv(exec.textureOf("tex"), GL_TEXTURE_BASE_LEVEL, &base);
    EXPECT_EQ(base, 0) << "the base level is put back after the pass";
  }
  unsetenv("RGRAPH_SUBRESOURCE_SAMPLING");
}

INSTANTIATE_TEST_SUITE_P(BothWays, SampledSubresource, ::testing::Values("views", "levels"));
