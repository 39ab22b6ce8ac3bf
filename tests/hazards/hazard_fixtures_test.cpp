// The hazard harness against planted hazards (issue 31): test-only pass types
// registered in-process (RendererOptions::registry), each relying on one
// thing the graph does not promise, each caught by its mode and named; a
// correct pipeline of the same types yields no finding.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/objects.h"
#include "rgraph/hazard_check.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "test_support.h"

namespace {

using namespace rgraph;
using namespace rgraph::decl;

std::string shader(const char* name) { return std::string(RGRAPH_TEST_DATA_DIR) + "/hazards/shaders/" + name; }
std::string pipeline(const char* name) { return std::string(RGRAPH_TEST_DATA_DIR) + "/hazards/pipelines/" + name; }

class FillPass : public gl::FullscreenPass {
 protected:
  void update(PassContext& ctx) override {
    const std::vector<double> c = ctx.params().getVector("color");
    color_.set(float(c[0]), float(c[1]), float(c[2]), float(c[3]));
  }
  ProgramUniform color_{this, "u_color"};
};

// (b): adds 0.25 to what its target holds, with no clear of its own.
class BlendOntoPass final : public FillPass {
  void update(PassContext& ctx) override {
    FillPass::update(ctx);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBlendEquation(GL_FUNC_ADD);
  }
};

// (a): declares an output and writes nothing.
class UnwrittenPass final : public PassInstance {
  void setup(PassContext&) override {}
  void execute(PassContext&) override {}
  uint32_t changedState() const override { return 0; }
};

// (d): fills its target, then leaves additive blending on, saying it changes nothing.
class LeakyPass final : public FillPass {
  void execute(PassContext& ctx) override {
    FillPass::execute(ctx);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
  }
  uint32_t changedState() const override { return 0; }
};

// (e): draws red into whatever framebuffer is bound; it declares none.
class StrayPass final : public PassInstance {
  void setup(PassContext&) override {}
  void execute(PassContext& ctx) override {
    const uint32_t program = ctx.program(0);
    glUseProgram(program);
    glProgramUniform4f(program, glGetUniformLocation(program, "u_color"), 1.0f, 0.0f, 0.0f, 1.0f);
    glBindVertexArray(ctx.emptyVertexArray());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  uint32_t changedState() const override { return kGlStateBindings; }
};

// (f): fills its target with the colour of a storage buffer it binds at 2
// and leaves bound there (allowed: buffer bindings are no promise).
class BufferOwnerPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const std::vector<double> c = ctx.params().getVector("color");
    const float color[4] = {float(c[0]), float(c[1]), float(c[2]), float(c[3])};
    if (!buffer_) {
      buffer_ = gl::createBuffer();
      glNamedBufferStorage(buffer_.id(), sizeof color, color, 0);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffer_.id());
  }
  gl::Buffer buffer_;
};

// (g): fills its target, leaving a nearest-filtering sampler object on unit 0.
class SamplerLeakPass final : public FillPass {
  void execute(PassContext& ctx) override {
    FillPass::execute(ctx);
    if (!sampler_) {
      sampler_ = gl::createSampler();
      glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glBindSampler(0, sampler_.id());
  }
  gl::Sampler sampler_;
};

PassTypeDesc type(const char* name, std::vector<SlotDecl> slots, const char* frag, std::vector<SamplerSlot> samplers,
                  std::function<std::unique_ptr<PassInstance>()> create) {
  PassTypeDesc t = passType(name, "hazard fixture");
  t.slots = std::move(slots);
  t.params = {param("color", ParamType::vec4, std::vector<double>{0.25, 0.25, 0.25, 1.0}, "colour")};
  if (frag) t.programs = gl::fullscreenPrograms(shader(frag), std::move(samplers));
  t.create = std::move(create);
  return t;
}

SlotDecl out(const char* name) { return slot(name, Access::color_attachment, true, SlotDecl::Load::never, "out"); }
SlotDecl outMultisampled(const char* name) {
  return slot(name, Access::color_attachment, true, SlotDecl::Load::never, "out", {}, true);
}
SlotDecl in(const char* name) { return slot(name, Access::sampled, true, SlotDecl::Load::never, "in"); }

const PassRegistry& fixtures() {
  static const PassRegistry types = [] {
    PassRegistry r = PassRegistry::builtins();
    std::string error;
    auto add = [&](PassTypeDesc t) { EXPECT_TRUE(r.add(std::move(t), &error)) << error; };
    add(type("hz_fill", {out("dst")}, "fill.frag", {}, [] { return std::make_unique<FillPass>(); }));
    add(type("hz_copy", {in("src"), out("dst")}, "copy.frag", {{"src", "u_src", 0}},
             [] { return std::make_unique<gl::FullscreenPass>(); }));
    add(type("hz_copy_unit3", {in("src"), out("dst")}, "copy3.frag", {{"src", "u_src", 3}},
             [] { return std::make_unique<gl::FullscreenPass>(); }));
    add(type("hz_add", {in("a"), in("b"), out("dst")}, "add.frag", {{"a", "u_a", 0}, {"b", "u_b", 1}},
             [] { return std::make_unique<gl::FullscreenPass>(); }));
    add(type("hz_unwritten", {out("dst")}, nullptr, {}, [] { return std::make_unique<UnwrittenPass>(); }));
    add(type("hz_blend_onto", {out("dst")}, "fill.frag", {}, [] { return std::make_unique<BlendOntoPass>(); }));
    add(type("hz_sneaky", {out("dst")}, "sneaky.frag", {}, [] { return std::make_unique<gl::FullscreenPass>(); }));
    add(type("hz_leaky", {out("dst")}, "fill.frag", {}, [] { return std::make_unique<LeakyPass>(); }));
    add(type("hz_stray", {}, "fill.frag", {}, [] { return std::make_unique<StrayPass>(); }));
    add(type("hz_buffer_owner", {out("dst")}, "buffer_fill.frag", {}, [] { return std::make_unique<BufferOwnerPass>(); }));
    add(type("hz_buffer_heir", {out("dst")}, "buffer_fill.frag", {},
             [] { return std::make_unique<gl::FullscreenPass>(); }));
    add(type("hz_sampler_leak", {out("dst")}, "fill.frag", {}, [] { return std::make_unique<SamplerLeakPass>(); }));
    add(type("hz_unwritten_ms", {outMultisampled("dst")}, nullptr, {},
             [] { return std::make_unique<UnwrittenPass>(); }));
    return r;
  }();
  return types;
}

HazardReport check(const char* file, const char* modes = nullptr) {
  testsupport::sharedGlContext();
  HazardCheckOptions o;
  o.scene = "";  // the fixtures draw no scene
  o.size = {32, 32};
  o.frames = 2;
  if (modes) {
    EXPECT_EQ(parseHazardModes(modes, o.modes), "");
  }
  o.renderer.registry = &fixtures();
  o.renderer.runChecks = false;  // the planted passes sample what their shaders do not declare
  HazardReport r = checkHazards(pipeline(file), o);
  std::cout << r.describe();  // the findings as a user sees them, in the test log
  return r;
}

// The finding of `mode`, or a failure listing the report.
const HazardFinding* findingOf(const HazardReport& r, const std::string& mode) {
  for (const HazardModeRun& run : r.runs)
    if (run.mode == mode && !run.findings.empty()) return &run.findings.front();
  ADD_FAILURE() << "no finding in mode " << mode << "\n" << r.describe();
  return nullptr;
}

// The finding of `mode`, checked to name `pass` and `resource`; nullptr
// (and a failure) when there is none.
const HazardFinding* expectFinding(const HazardReport& r, const std::string& mode, const char* pass,
                                   const char* resource) {
  const HazardFinding* f = findingOf(r, mode);
  if (!f) return nullptr;
  EXPECT_EQ(f->pass, pass) << mode << ": " << f->message;
  if (resource) {
    EXPECT_EQ(f->resource, resource) << mode << ": " << f->message;
  }
  return f;
}

// `file` run in `mode` only: its finding names `pass` and `resource`, every
// one of the 32x32 pixels differing.
const HazardFinding* expectWholeResource(const char* file, const char* mode, const char* pass,
                                         const char* resource, HazardReport& r) {
  r = check(file, mode);
  const HazardFinding* f = expectFinding(r, mode, pass, resource);
  if (f) {
    EXPECT_EQ(f->pixels, 32u * 32u) << f->message;
  }
  return f;
}

// `file` under state-scramble: the state check after `pass` fails, saying `what`.
void expectStateCheck(const char* file, const char* pass, const char* what) {
  const HazardReport r = check(file, "state-scramble");
  if (const HazardFinding* f = expectFinding(r, "state-scramble", pass, nullptr)) {
    EXPECT_NE(f->message.find(what), std::string::npos) << f->message;
  }
}

TEST(HazardFixtures, CorrectPipelineHasNoFinding) {
  const HazardReport r = check("correct.json");
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.hazardFree()) << r.describe();
  ASSERT_EQ(r.runs.size(), 8u) << r.describe();  // six modes, reorder as three orders
  for (const HazardModeRun& run : r.runs) EXPECT_GT(run.comparedPixels, 0u) << run.mode;
}

TEST(HazardFixtures, ReadOfAnUnwrittenTransientIsCaughtByPoison) {
  HazardReport r;
  const HazardFinding* f = expectWholeResource("unwritten.json", "poison", "unwritten", "t", r);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->where.line, 9) << f->message;
  EXPECT_NE(f->message.find("unwritten.json:9:"), std::string::npos) << f->message;
}

TEST(HazardFixtures, RelyingOnAnAliasedTargetsClearIsCaughtByNoAliasAndPoison) {
  const HazardReport r = check("aliased-clear.json", "no-alias,poison");
  for (const char* mode : {"no-alias", "poison"}) {
    const HazardFinding* f = expectFinding(r, mode, "blend_onto", "t2");
    if (f) {
      EXPECT_EQ(f->pixels, 32u * 32u) << mode;
    }
  }
}

TEST(HazardFixtures, ReadWithoutAnEdgeIsCaughtByReorderAndStateScramble) {
  const HazardReport r = check("no-edge.json", "reorder:3,state-scramble");
  expectFinding(r, "state-scramble", "sneaky", "r2");
  bool reorderFound = false;
  for (const HazardFinding& f : r.findings())
    if (f.mode.rfind("reorder", 0) == 0) {
      reorderFound = true;
      EXPECT_EQ(f.pass, "sneaky") << f.message;
      EXPECT_EQ(f.resource, "r2") << f.message;
    }
  EXPECT_TRUE(reorderFound) << r.describe();
}

TEST(HazardFixtures, BlendingLeftOnIsCaughtByStateScramble) {
  expectStateCheck("blend-left-on.json", "leaky", "GL_BLEND is on");
}

TEST(HazardFixtures, AnUndeclaredColourWriteIsCaughtByStateScramble) {
  const HazardReport r = check("undeclared-write.json", "state-scramble");
  const HazardFinding* f = expectFinding(r, "state-scramble", "stray", "a");
  ASSERT_TRUE(f);
  EXPECT_FALSE(f->declared) << f->message;
  EXPECT_NE(f->message.find("does not declare writing"), std::string::npos) << f->message;
}

// (f) A buffer binding left by an earlier pass: state-scramble binds a buffer
// of its own at every uniform and storage binding point before each pass.
TEST(HazardFixtures, AnInheritedBufferBindingIsCaughtByStateScramble) {
  HazardReport r;
  EXPECT_TRUE(expectWholeResource("inherited-buffer.json", "state-scramble", "heir", "b", r));
}

// (g) A sampler object left bound: every pass is promised sampler 0 on every
// unit, so the pass that leaves one is named (the one after it did nothing wrong).
TEST(HazardFixtures, ASamplerLeftBoundIsCaughtByStateScramble) {
  expectStateCheck("sampler-left-bound.json", "leaky_sampler", "left sampler object");
}

// (h) Multisampled targets are compared sample by sample: the pass that left
// the samples unwritten is named, not the resolve after it, which is where a
// comparison of single-sample textures alone would first see it.
TEST(HazardFixtures, AnUnwrittenMultisampledTargetIsNamedWithItsPass) {
  HazardReport r;
  const HazardFinding* f = expectWholeResource("msaa-unwritten.json", "poison", "unwritten_ms", "ms", r);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->comparedPixels, 32u * 32u);
}

}  // namespace
