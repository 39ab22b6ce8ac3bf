#include <GL/glcorearb.h>

#include <cmath>

#include "gl_test_util.h"
#include "rgraph/error.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr Extent kSize{64, 64};

// Every pixel of a top-down RGBA8 image equals `want`; returns mismatches.
size_t countNot(const std::vector<uint8_t>& rgba, std::array<uint8_t, 4> want) {
  size_t bad = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4)
    if (rgba[i] != want[0] || rgba[i + 1] != want[1] || rgba[i + 2] != want[2] || rgba[i + 3] != want[3]) ++bad;
  return bad;
}

std::string px(const std::vector<uint8_t>& rgba, size_t i) {
  return std::to_string(rgba[i * 4]) + "," + std::to_string(rgba[i * 4 + 1]) + "," + std::to_string(rgba[i * 4 + 2]) +
         "," + std::to_string(rgba[i * 4 + 3]);
}

const PassRegistry& builtins() { return processRegistry(); }

}  // namespace

TEST(BuiltinPasses, AreRegistered) {
  EXPECT_TRUE(PassRegistry::builtinErrors().empty());
  for (const char* name : {"clear", "fullscreen", "blit", "present"}) {
    const PassTypeDesc* d = builtins().find(name);
    ASSERT_NE(d, nullptr) << name;
    EXPECT_TRUE(d->create) << name;
    EXPECT_FALSE(d->description.empty()) << name;
    for (const auto& p : d->params) EXPECT_FALSE(p.description.empty()) << name << "." << p.name;
  }
  const PassTypeDesc* fs = builtins().find("fullscreen");
  ASSERT_NE(fs->findSlot("color"), nullptr);
  EXPECT_EQ(fs->findSlot("color")->load, SlotDecl::Load::optional);
  EXPECT_FALSE(fs->findSlot("input0")->required);
  ASSERT_NE(fs->findParam("shader"), nullptr);
  EXPECT_EQ(fs->findParam("shader")->type, ParamType::shader);
  const ParamDecl* filter = builtins().find("blit")->findParam("filter");
  ASSERT_NE(filter, nullptr);
  EXPECT_EQ(filter->choices, (std::vector<std::string>{"nearest", "linear"}));
}

TEST_F(GlTest, ClearThenPresent) {
  GraphBuilder g;
  g.texture("hdr", Format::rgba16f).output("out");
  g.pass("clear", "clear", {writeUse("color", Access::color_attachment, "hdr")},
         params({{"color", std::vector<double>{0.2, 0.4, 0.6, 1.0}}}));
  g.present("hdr");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize(kSize);
  ASSERT_EQ(exec.plan().order.size(), 2u);
  exec.renderFrame();
  EXPECT_EQ(exec.outputExtent(), kSize);
  auto rgba = exec.readOutputRGBA8();
  ASSERT_EQ(rgba.size(), 64u * 64u * 4u);
  EXPECT_EQ(countNot(rgba, {51, 102, 153, 255}), 0u) << px(rgba, 0);
}

TEST_F(GlTest, GradientIntoOutputIsExact) {
  GraphBuilder g;
  g.output("out");
  g.gradient("out");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize(kSize);
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

TEST_F(GlTest, InvertTwiceThroughAliasedTexturesIsIdentity) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("b", Format::rgba8).texture("c", Format::rgba8).output("out");
  g.gradient("a");
  g.pass("invert1", "fullscreen",
         {readUse("input0", Access::sampled, "a"), writeUse("color", Access::color_attachment, "b")},
         params({{"shader", std::string("invert.frag")}}));
  g.pass("invert2", "fullscreen",
         {readUse("input0", Access::sampled, "b"), writeUse("color", Access::color_attachment, "c")},
         params({{"shader", std::string("invert.frag")}}));
  g.present("c");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize(kSize);
  const Plan& plan = exec.plan();
  ASSERT_TRUE(plan.ok());
  // a dies when invert1 ends; c starts after: they share one physical texture.
  EXPECT_TRUE(plan.resources[0].physical.valid());
  EXPECT_EQ(plan.resources[0].physical, plan.resources[2].physical);
  EXPECT_NE(plan.resources[0].physical, plan.resources[1].physical);
  EXPECT_EQ(plan.physical.size(), 2u);
  EXPECT_EQ(exec.textureOf("a"), exec.textureOf("c"));
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
  // A second frame reuses everything and gives the same image.
  uint32_t outTex = exec.outputTexture();
  exec.renderFrame();
  EXPECT_EQ(exec.outputTexture(), outTex);
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

TEST_F(GlTest, SingleInvertIsComplement) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).output("out");
  g.gradient("a");
  g.pass("invert", "fullscreen",
         {readUse("input0", Access::sampled, "a"), writeUse("color", Access::color_attachment, "out")},
         params({{"shader", std::string("invert.frag")}}));
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({16, 8});
  exec.renderFrame();
  auto rgba = exec.readOutputRGBA8();
  size_t bad = 0;
  for (uint32_t row = 0; row < 8; ++row)
    for (uint32_t x = 0; x < 16; ++x) {
      auto g0 = gradientPixel(x, 7 - row);
      const uint8_t* p = &rgba[(row * 16 + x) * 4];
      if (p[0] != 255 - g0[0] || p[1] != 255 - g0[1] || p[2] != 255 - g0[2] || p[3] != 255) ++bad;
    }
  EXPECT_EQ(bad, 0u);
}

TEST_F(GlTest, BlitColourIsExact) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).output("out");
  g.gradient("a");
  g.pass("copy", "blit", {readUse("src", Access::blit_src, "a"), writeUse("dst", Access::blit_dst, "out")},
         params({{"filter", std::string("nearest")}}));
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize(kSize);
  exec.renderFrame();
  EXPECT_TRUE(outputIsGradient(exec, kSize));
}

TEST_F(GlTest, BlitDownscaleNearestPicksSourceTexels) {
  GraphBuilder g;
  g.texture("a", Format::rgba8, SizeSpec::absolute(64, 64)).output("out");
  g.gradient("a");
  g.pass("down", "blit", {readUse("src", Access::blit_src, "a"), writeUse("dst", Access::blit_dst, "out")},
         params({{"filter", std::string("nearest")}}));
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({32, 32});
  exec.renderFrame();
  auto rgba = exec.readOutputRGBA8();
  // Destination pixel centre (x + 0.5) maps to source 2x + 1.
  size_t bad = 0;
  for (uint32_t row = 0; row < 32; ++row)
    for (uint32_t x = 0; x < 32; ++x) {
      auto want = gradientPixel(2 * x + 1, 2 * (31 - row) + 1);
      const uint8_t* p = &rgba[(row * 32 + x) * 4];
      if (p[0] != want[0] || p[1] != want[1] || p[2] != want[2]) ++bad;
    }
  EXPECT_EQ(bad, 0u);
}

TEST_F(GlTest, DepthWriteAndDepthBlitAreExact) {
  GraphBuilder g;
  g.texture("color", Format::rgba8).texture("depth", Format::depth32f).texture("depth_copy", Format::depth32f);
  g.output("out");
  g.pass("draw", "fullscreen",
         {writeUse("color", Access::color_attachment, "color"), writeUse("depth", Access::depth_attachment, "depth")},
         params({{"shader", std::string("depth_gradient.frag")}}));
  g.pass("copy_depth", "blit",
         {readUse("src", Access::blit_src, "depth"), writeUse("dst", Access::blit_dst, "depth_copy")}, {},
         /*sideEffect=*/true);
  g.present("color");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize(kSize);
  ASSERT_EQ(exec.plan().order.size(), 3u);
  exec.renderFrame();
  for (const char* name : {"depth", "depth_copy"}) {
    auto d = exec.readTextureRGBA32F(name);
    ASSERT_EQ(d.size(), 64u * 64u * 4u);
    size_t bad = 0;
    for (uint32_t row = 0; row < 64; ++row)
      for (uint32_t x = 0; x < 64; ++x) {
        float want = static_cast<float>(x + 64 * (63 - row)) / 4096.0f;
        if (d[(row * 64 + x) * 4] != want) ++bad;
      }
    EXPECT_EQ(bad, 0u) << name << ": first value " << d[0];
  }
}

TEST_F(GlTest, DepthStencilBlit) {
  GraphBuilder g;
  g.texture("color", Format::rgba8).texture("depth", Format::depth24_stencil8);
  g.texture("depth_copy", Format::depth24_stencil8).output("out");
  g.pass("draw", "fullscreen",
         {writeUse("color", Access::color_attachment, "color"), writeUse("depth", Access::depth_attachment, "depth")},
         params({{"shader", std::string("depth_gradient.frag")}}));
  g.pass("copy_depth", "blit",
         {readUse("src", Access::blit_src, "depth"), writeUse("dst", Access::blit_dst, "depth_copy")}, {}, true);
  g.present("color");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({32, 32});
  exec.renderFrame();
  auto a = exec.readTextureRGBA32F("depth");
  auto b = exec.readTextureRGBA32F("depth_copy");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a, b);  // the blit copies the stored 24-bit values exactly
  float want = static_cast<float>(5 + 64 * 31) / 4096.0f;  // top row, x = 5
  EXPECT_NEAR(a[5 * 4], want, 1e-6f);
}

TEST_F(GlTest, ResourceClearAndDepthTest) {
  // Depth cleared to 0.5 by its resource clear value; draw with depth_func
  // "less": only pixels whose depth (x + 64y)/4096 < 0.5 (the bottom 32 rows) pass.
  GraphBuilder g;
  g.texture("color", Format::rgba8, SizeSpec::output(), std::vector<float>{0.0f, 0.0f, 1.0f, 1.0f});
  g.texture("depth", Format::depth32f, SizeSpec::output(), std::vector<float>{0.5f});
  g.output("out");
  g.pass("draw", "fullscreen",
         {writeUse("color", Access::color_attachment, "color"), writeUse("depth", Access::depth_attachment, "depth")},
         params({{"shader", std::string("solid_color.frag")},
                 {"color", std::vector<double>{1.0, 0.0, 0.0, 1.0}},
                 {"depth_func", std::string("less")}}));
  g.present("color");
  // solid_color.frag does not write gl_FragDepth: the triangle's depth is 0.5
  // everywhere, which does not pass "less" against 0.5, so the image stays blue.
  {
    Executor exec(g.config(), builtins(), *shaders);
    exec.resize({16, 16});
    exec.renderFrame();
    EXPECT_EQ(countNot(exec.readOutputRGBA8(), {0, 0, 255, 255}), 0u);
  }
  g.config().params[0].set("shader", std::string("depth_gradient.frag"));
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({64, 64});
  exec.renderFrame();
  auto rgba = exec.readOutputRGBA8();
  size_t bad = 0;
  for (uint32_t row = 0; row < 64; ++row)
    for (uint32_t x = 0; x < 64; ++x) {
      uint32_t yGl = 63 - row;
      const uint8_t* p = &rgba[(row * 64 + x) * 4];
      bool passed = yGl < 32;
      uint8_t grey = static_cast<uint8_t>(std::lround(static_cast<float>(x + 64 * yGl) / 4096.0f * 255.0f));
      if (passed ? (p[0] != grey || p[1] != grey || p[2] != grey) : (p[0] != 0 || p[1] != 0 || p[2] != 255)) ++bad;
    }
  EXPECT_EQ(bad, 0u);
  auto depth = exec.readTextureRGBA32F("depth");
  EXPECT_EQ(depth[0], 0.5f);                                       // top-left: failed, keeps the clear
  EXPECT_EQ(depth[(63 * 64) * 4], 0.0f);                           // bottom-left: depth 0 written
}

TEST_F(GlTest, LoadAndAdditiveBlend) {
  GraphBuilder g;
  g.texture("hdr", Format::rgba16f, SizeSpec::output(), std::vector<float>{0.25f, 0.5f, 0.0f, 1.0f});
  g.output("out");
  g.pass("add", "fullscreen", {writeUse("color", Access::color_attachment, "hdr")},
         params({{"shader", std::string("solid_color.frag")}, {"color", std::vector<double>{0.125, 0.0, 0.0, 0.0}},
                 {"blend", std::string("additive")}}));
  g.pass("add_again", "fullscreen", {writeUse("color", Access::color_attachment, "hdr_2", "hdr")},
         params({{"shader", std::string("solid_color.frag")}, {"color", std::vector<double>{0.0, 0.25, 0.0, 0.0}},
                 {"blend", std::string("additive")}}));
  g.present("hdr_2");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({8, 8});
  exec.renderFrame();
  auto f = exec.readTextureRGBA32F("hdr_2");
  EXPECT_EQ(f[0], 0.375f);
  EXPECT_EQ(f[1], 0.75f);
  EXPECT_EQ(f[2], 0.0f);
  EXPECT_EQ(f[3], 1.0f);
  auto rgba = exec.readOutputRGBA8();
  EXPECT_EQ(countNot(rgba, {96, 191, 0, 255}), 0u) << px(rgba, 0);  // 0.375*255 = 95.6, 0.75*255 = 191.25
}

TEST_F(GlTest, MultipleRenderTargetsFollowSlotOrder) {
  GraphBuilder g;
  g.texture("first", Format::rgba8).texture("second", Format::rgba8).output("out");
  // Uses listed in the opposite order to the slot declarations on purpose.
  g.pass("mrt", "fullscreen",
         {writeUse("color1", Access::color_attachment, "second"), writeUse("color", Access::color_attachment, "first")},
         params({{"shader", std::string("mrt.frag")}, {"color", std::vector<double>{0.2, 0.4, 0.6, 1.0}}}));
  g.present("second");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({8, 8});
  exec.renderFrame();
  EXPECT_EQ(countNot(exec.readOutputRGBA8(), {204, 153, 102, 255}), 0u);
  auto first = exec.readTextureRGBA32F("first");
  EXPECT_FLOAT_EQ(first[0], 51.0f / 255.0f);
}

TEST_F(GlTest, MultisampleResolveByBlit) {
  GraphBuilder g;
  g.texture("ms", Format::rgba8, SizeSpec::output(), std::nullopt, 4).texture("resolved", Format::rgba8);
  g.output("out");
  g.pass("draw", "fullscreen", {writeUse("color", Access::color_attachment, "ms")},
         params({{"shader", std::string("solid_color.frag")}, {"color", std::vector<double>{0.2, 0.4, 0.6, 1.0}}}));
  g.pass("resolve", "blit",
         {readUse("src", Access::blit_src, "ms", true), writeUse("dst", Access::blit_dst, "resolved")},
         params({{"filter", std::string("nearest")}}));
  g.present("resolved");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({16, 16});
  exec.renderFrame();
  EXPECT_EQ(countNot(exec.readOutputRGBA8(), {51, 102, 153, 255}), 0u);
}

TEST_F(GlTest, SrgbOutputEncodesLinearValues) {
  // Linear values whose sRGB encodings are exact bytes: decode(k/255).
  auto decode = [](double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); };
  std::vector<double> lin = {decode(128 / 255.0), decode(64 / 255.0), decode(200 / 255.0), 1.0};
  for (bool srgbTarget : {true, false}) {
    GraphBuilder g;
    g.texture("hdr", Format::rgba32f).output("out", srgbTarget ? Format::srgb8_alpha8 : Format::rgba8);
    g.pass("clear", "clear", {writeUse("color", Access::color_attachment, "hdr")}, params({{"color", lin}}));
    g.pass("present", "present",
           {readUse("src", Access::sampled, "hdr"), writeUse("dst", Access::color_attachment, "out")},
           params({{"gamma", true}}));
    Executor exec(g.config(), builtins(), *shaders);
    exec.resize({8, 8});
    exec.renderFrame();
    EXPECT_EQ(exec.outputFormat(), srgbTarget ? Format::srgb8_alpha8 : Format::rgba8);
    auto rgba = exec.readOutputRGBA8();
    EXPECT_EQ(countNot(rgba, {128, 64, 200, 255}), 0u) << (srgbTarget ? "srgb8_alpha8: " : "rgba8+gamma: ")
                                                       << px(rgba, 0);
  }
}

TEST_F(GlTest, ResizeRebuildsTexturesAndKeepsPixelsRight) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("half", Format::rgba16f, SizeSpec::relative(0.5f)).output("out");
  g.gradient("a");
  g.pass("small", "fullscreen", {writeUse("color", Access::color_attachment, "half")},
         params({{"shader", std::string("solid_color.frag")}}), true);
  g.present("a");
  Executor exec(g.config(), builtins(), *shaders);
  for (Extent e : {Extent{32, 32}, Extent{48, 16}, Extent{7, 33}}) {
    exec.resize(e);
    EXPECT_EQ(exec.outputExtent(), e);
    exec.renderFrame();
    EXPECT_TRUE(outputIsGradient(exec, e)) << e.width << "x" << e.height;
    auto half = exec.readTextureRGBA32F("half");
    Extent he = resolveSize(SizeSpec::relative(0.5f), e);
    EXPECT_EQ(half.size(), static_cast<size_t>(he.width) * he.height * 4);
  }
  uint32_t tex = exec.outputTexture();
  exec.resize({7, 33});  // same size: nothing rebuilt
  EXPECT_EQ(exec.outputTexture(), tex);
}

TEST_F(GlTest, HundredResizesLeakNoGlObjects) {
  using gl::ObjectKind;
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("b", Format::rgba16f).texture("d", Format::depth24_stencil8).output("out");
  g.pass("draw", "fullscreen",
         {writeUse("color", Access::color_attachment, "a"), writeUse("depth", Access::depth_attachment, "d")},
         params({{"shader", std::string("depth_gradient.frag")}}));
  g.pass("invert", "fullscreen",
         {readUse("input0", Access::sampled, "a"), writeUse("color", Access::color_attachment, "b")},
         params({{"shader", std::string("invert.frag")}}));
  g.present("b");
  const ObjectKind kinds[] = {ObjectKind::texture, ObjectKind::framebuffer, ObjectKind::buffer,
                              ObjectKind::vertex_array, ObjectKind::query, ObjectKind::program};
  auto snapshot = [&] {
    std::vector<int64_t> v;
    for (ObjectKind k : kinds) v.push_back(gl::liveObjects(k));
    return v;
  };
  auto before = snapshot();
  {
    Executor exec(g.config(), builtins(), *shaders);
    exec.resize({16, 16});
    exec.renderFrame();
    auto afterFirst = snapshot();
    size_t owned = exec.ownedObjects();
    for (int i = 0; i < 100; ++i) {
      exec.resize({static_cast<uint32_t>(8 + i % 13), static_cast<uint32_t>(8 + i % 7)});
      exec.renderFrame();
    }
    exec.resize({16, 16});
    exec.renderFrame();
    EXPECT_EQ(snapshot(), afterFirst);
    EXPECT_EQ(exec.ownedObjects(), owned);
  }
  auto after = snapshot();
  // Programs stay cached in the ShaderLibrary; everything else is gone.
  for (size_t i = 0; i + 1 < std::size(kinds); ++i)
    EXPECT_EQ(after[i], before[i]) << gl::objectKindName(kinds[i]);
}

TEST_F(GlTest, TimingsPerExecutedPass) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).texture("unused", Format::rgba8).output("out");
  g.gradient("a");
  g.pass("culled", "clear", {writeUse("color", Access::color_attachment, "unused")});
  g.present("a");
  Executor exec(g.config(), builtins(), *shaders);
  exec.resize({16, 16});
  EXPECT_TRUE(exec.plan().passes[1].culled);
  exec.renderFrame();
  ASSERT_EQ(exec.timings().size(), 2u);
  EXPECT_EQ(exec.timings()[0].name, "gradient");
  EXPECT_EQ(exec.timings()[1].name, "present");
  for (const auto& t : exec.timings()) EXPECT_GE(t.ms, 0.0);
  if (ctx().isSoftware()) {
    EXPECT_TRUE(exec.cpuTimed());
  }
}

TEST_F(GlTest, GraphErrorsThrowWithDiagnostics) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).output("out");
  g.present("a");
  Executor exec(g.config(), builtins(), *shaders);
  try {
    exec.resize({16, 16});
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("error"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'a'"), std::string::npos) << msg;
  }
  EXPECT_THROW(exec.renderFrame(), RuntimeError);
}

TEST_F(GlTest, UnknownPassTypeThrows) {
  GraphBuilder g;
  g.output("out");
  g.pass("mystery", "no_such_type", {writeUse("color", Access::color_attachment, "out")});
  Executor exec(g.config(), builtins(), *shaders);
  try {
    exec.resize({16, 16});
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_type"), std::string::npos) << e.what();
  }
}

TEST_F(GlTest, ShaderErrorInPassNamesFileAndLine) {
  GraphBuilder g;
  g.output("out");
  g.pass("broken", "fullscreen", {writeUse("color", Access::color_attachment, "out")},
         params({{"shader", std::string("bad_syntax.frag")}}));
  Executor exec(g.config(), builtins(), *shaders);
  try {
    exec.resize({16, 16});
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("bad_syntax.frag:7:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("broken"), std::string::npos) << msg;
  }
  // The executor is left empty, not half-built.
  EXPECT_EQ(exec.ownedObjects(), 0u);
}

TEST_F(GlTest, PassInstancesSeeTheirBindings) {
  // A test-only pass type, registered in a copy of the built-in registry.
  struct Seen {
    bool called = false;
    Extent fbExtent, outExtent;
    Format dstFormat = Format::rgba8;
    bool srcBound = false, optionalBound = true, loads = true;
    uint32_t fbo = 0, dstTex = 0;
  };
  static Seen seen;
  struct Probe final : PassInstance {
    void execute(PassContext& ctx) override {
      seen.called = true;
      seen.fbExtent = ctx.framebufferExtent();
      seen.outExtent = ctx.outputExtent();
      seen.dstFormat = ctx.format("dst");
      seen.srcBound = ctx.bound("src");
      seen.optionalBound = ctx.bound("extra");
      seen.loads = ctx.loads("dst");
      seen.fbo = ctx.framebuffer();
      seen.dstTex = ctx.texture("dst");
      glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{1, 0, 0, 1}.data());
    }
  };
  PassRegistry reg = builtins();
  PassTypeDesc probe;
  probe.name = "probe";
  probe.description = "test";
  probe.slots.resize(3);
  probe.slots[0].name = "src";
  probe.slots[1].name = "extra";
  probe.slots[1].required = false;
  probe.slots[2].name = "dst";
  probe.slots[2].access = Access::color_attachment;
  probe.create = [] { return std::make_unique<Probe>(); };
  ASSERT_TRUE(reg.add(probe));

  GraphBuilder g;
  g.texture("a", Format::rgba16f, SizeSpec::absolute(10, 6)).output("out");
  g.pass("clear", "clear", {writeUse("color", Access::color_attachment, "a")});
  g.pass("probe", "probe", {readUse("src", Access::sampled, "a"), writeUse("dst", Access::color_attachment, "out")});
  Executor exec(g.config(), reg, *shaders);
  exec.resize({12, 9});
  exec.renderFrame();
  EXPECT_TRUE(seen.called);
  EXPECT_EQ(seen.fbExtent, (Extent{12, 9}));
  EXPECT_EQ(seen.outExtent, (Extent{12, 9}));
  EXPECT_EQ(seen.dstFormat, Format::rgba8);
  EXPECT_TRUE(seen.srcBound);
  EXPECT_FALSE(seen.optionalBound);
  EXPECT_FALSE(seen.loads);
  EXPECT_NE(seen.fbo, 0u);
  EXPECT_EQ(seen.dstTex, exec.outputTexture());
  EXPECT_EQ(countNot(exec.readOutputRGBA8(), {255, 0, 0, 255}), 0u);
}
