// PassInstance::changedState: the executor puts back before a pass only the
// state groups earlier passes said they may leave changed, and
// Executor::setStateChecks reads the state back to check those answers.
#include <GL/glcorearb.h>

#include <filesystem>

#include "gl_test_util.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

bool blendSeen = false;

// Turns blending on and answers `declared`.
template <uint32_t declared>
struct BlendLeaver final : PassInstance {
  void execute(PassContext& ctx) override {
    glEnable(GL_BLEND);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{0, 0, 0, 1}.data());
  }
  uint32_t changedState() const override { return declared; }
};
// Records whether blending was on when it ran.
struct BlendLooker final : PassInstance {
  void execute(PassContext& ctx) override {
    blendSeen = glIsEnabled(GL_BLEND);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{1, 1, 1, 1}.data());
  }
  uint32_t changedState() const override { return 0; }
};

// Binds program 0 with a raw GL call and answers `declared`.
template <uint32_t declared>
struct ProgramUnbinder final : PassInstance {
  void execute(PassContext& ctx) override {
    glUseProgram(0);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{0, 0, 0, 1}.data());
  }
  uint32_t changedState() const override { return declared; }
};
// Records the executor's binding record and the program GL has bound.
uint32_t recordedProgram = 0, actualProgram = 0;
struct BindingLooker final : PassInstance {
  void execute(PassContext& ctx) override {
    recordedProgram = ctx.bindings() ? ctx.bindings()->program : 0;
    GLint p = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &p);
    actualProgram = static_cast<uint32_t>(p);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{1, 1, 1, 1}.data());
  }
  uint32_t changedState() const override { return 0; }
};

// The RuntimeError a frame throws ("no error" when it throws none).
std::string frameError(Executor& exec) {
  try {
    exec.renderFrame();
  } catch (const RuntimeError& e) {
    return e.what();
  }
  return "no error";
}

PassTypeDesc probeType(const std::string& name, std::function<std::unique_ptr<PassInstance>()> create) {
  PassTypeDesc d;
  d.name = name;
  d.description = "test";
  d.slots.resize(2);
  d.slots[0].name = "src";
  d.slots[0].required = false;
  d.slots[1].name = "dst";
  d.slots[1].access = Access::color_attachment;
  d.create = std::move(create);
  return d;
}

struct StateTest : GlTest {
  PassRegistry reg = PassRegistry::builtins();
  void SetUp() override {
    GlTest::SetUp();
    ASSERT_TRUE(reg.add(probeType("honest", [] { return std::make_unique<BlendLeaver<kGlStateBlend>>(); })));
    ASSERT_TRUE(reg.add(probeType("lying", [] { return std::make_unique<BlendLeaver<0>>(); })));
    ASSERT_TRUE(reg.add(probeType("looker", [] { return std::make_unique<BlendLooker>(); })));
    ASSERT_TRUE(reg.add(probeType("binding_looker", [] { return std::make_unique<BindingLooker>(); })));
    ASSERT_TRUE(reg.add(
        probeType("honest_unbinder", [] { return std::make_unique<ProgramUnbinder<kGlStateBindings>>(); })));
    ASSERT_TRUE(reg.add(probeType("lying_unbinder", [] { return std::make_unique<ProgramUnbinder<0>>(); })));
  }
  // A gradient, then `middle` (reads it, writes elsewhere), then the same
  // gradient again into the output: the first and last passes draw with
  // one program, so the last binds it only if the record says it must.
  PipelineConfig bindingGraph(const std::string& middle) {
    GraphBuilder g;
    g.texture("a", Format::rgba8).texture("b", Format::rgba8).output("out");
    g.pass("gradient", "fullscreen", {writeUse("color", Access::color_attachment, "a")},
           params({{"shader", std::string("gradient.frag")}}));
    g.pass("middle", middle, {readUse("src", Access::sampled, "a"), writeUse("dst", Access::color_attachment, "b")},
           {}, /*sideEffect=*/true);
    g.pass("again", "fullscreen", {writeUse("color", Access::color_attachment, "out")},
           params({{"shader", std::string("gradient.frag")}}));
    return g.config();
  }
  // `leaver` then the looker, which reads what the leaver wrote.
  PipelineConfig graph(const std::string& leaver) {
    GraphBuilder g;
    g.texture("a", Format::rgba8).output("out");
    g.pass("leave", leaver, {writeUse("dst", Access::color_attachment, "a")});
    g.pass("look", "looker", {readUse("src", Access::sampled, "a"), writeUse("dst", Access::color_attachment, "out")});
    return g.config();
  }
};

TEST_F(StateTest, StateAPassSaysItChangedIsPutBack) {
  Executor exec(graph("honest"), reg, *shaders);
  exec.setStateChecks(true);
  exec.resize({8, 8});
  blendSeen = true;
  exec.renderFrame();
  EXPECT_FALSE(blendSeen);
}

// What the executor trusts: a pass that leaves blending on but says it
// changes nothing leaks it into the next pass (the reset was skipped), and
// the state checks name it.
TEST_F(StateTest, AWrongAnswerLeaksAndTheChecksNameThePass) {
  Executor exec(graph("lying"), reg, *shaders);
  exec.resize({8, 8});
  blendSeen = false;
  exec.renderFrame();
  EXPECT_TRUE(blendSeen);
  exec.setStateChecks(true);
  const std::string msg = frameError(exec);
  EXPECT_NE(msg.find("pass 'leave' of type 'lying' left state changed: GL_BLEND is on"), std::string::npos) << msg;
  EXPECT_NE(msg.find("changedState()"), std::string::npos) << msg;
  glDisable(GL_BLEND);
}

// The built-in passes' answers hold: every shipped pipeline made of
// built-in pass types (adapted to the LearnOpenGL scene, as rgraph render
// does), and fullscreen passes that blend and depth-test.
TEST_F(StateTest, BuiltInPassesAnswerTruthfully) {
  const Scene scene = makeLearnOpenGLScene();
  std::vector<std::pair<std::string, PipelineConfig>> pipelines;
  for (const char* dir : {"/pipelines", "/pipelines/examples"})
    for (const auto& f : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + dir)) {
      if (f.path().extension() != ".json") continue;
      PipelineConfig cfg = loadPipelineFileOrThrow(f.path().string());
      if (!cfg.plugins.empty()) continue;  // plugin types keep the default answer (all)
      adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
      pipelines.emplace_back(f.path().filename().string(), std::move(cfg));
    }
  ASSERT_GE(pipelines.size(), 10u);
  pipelines.emplace_back("fullscreen blend and depth", loadPipelineTextOrThrow(R"({"version": 1,
    "resources": {"c": {"format": "rgba16f", "size": "output"}, "d": {"format": "depth32f", "size": "output"},
                  "out": {"format": "rgba8", "size": "output"}},
    "passes": [
      {"name": "base", "type": "fullscreen", "params": {"shader": "gradient.frag"}, "outputs": {"color": "c"}},
      {"name": "depth", "type": "fullscreen", "params": {"shader": "solid_color.frag", "depth_func": "always"},
       "outputs": {"color": "c1", "depth": "d"}, "inputs": {"color": "c"}},
      {"name": "alpha", "type": "fullscreen", "params": {"shader": "solid_color.frag", "blend": "alpha",
       "color": [1, 0, 0, 0.5]}, "inputs": {"color": "c1"}, "outputs": {"color": "c2"}},
      {"name": "add", "type": "fullscreen", "params": {"shader": "solid_color.frag", "blend": "additive"},
       "inputs": {"color": "c2"}, "outputs": {"color": "c3"}},
      {"name": "tonemap", "type": "tonemap", "inputs": {"hdr": "c3"}, "outputs": {"output": "out"}}],
    "output": "out"})", "<state test>"));
  for (auto& [name, cfg] : pipelines) {
    SCOPED_TRACE(name);
    Executor exec(cfg, processRegistry(), *shaders, &scene);
    exec.setStateChecks(true);
    exec.resize({32, 24});
    EXPECT_NO_THROW(exec.renderFrame());
    EXPECT_NO_THROW(exec.renderFrame());
  }
}

}  // namespace

namespace {

// Fullscreen passes bind their framebuffer, program and vertex array through
// PassContext::bindings(): the record survives a pass that binds nothing, so
// the next pass with the same program skips its bind.
TEST_F(StateTest, BindingsTheRecordOutlivesAPassThatBindsNothing) {
  GraphBuilder g;
  g.texture("a", Format::rgba8).output("out");
  g.pass("gradient", "fullscreen", {writeUse("color", Access::color_attachment, "a")},
         params({{"shader", std::string("gradient.frag")}}));
  g.pass("look", "binding_looker",
         {readUse("src", Access::sampled, "a"), writeUse("dst", Access::color_attachment, "out")});
  Executor exec(g.config(), reg, *shaders);
  exec.setStateChecks(true);
  exec.resize({8, 8});
  recordedProgram = actualProgram = 0;
  exec.renderFrame();
  EXPECT_NE(actualProgram, 0u);
  EXPECT_EQ(recordedProgram, actualProgram);
}

// A pass that binds with raw GL calls and says so (kGlStateBindings) makes the
// executor forget its record; one that does not say so leaves the next pass
// drawing with no program, and the state checks name it.
TEST_F(StateTest, BindingsARawBindMustBeDeclared) {
  {
    const PipelineConfig cfg = bindingGraph("honest_unbinder");
    Executor exec(cfg, reg, *shaders);
    exec.setStateChecks(true);
    exec.resize({8, 8});
    std::vector<std::string> order;
    for (PassIndex p : exec.plan().order) order.push_back(cfg.graph.passes[p.value()].name);
    ASSERT_EQ(order, (std::vector<std::string>{"gradient", "middle", "again"}));
    ASSERT_NO_THROW(exec.renderFrame());
    EXPECT_EQ(gradientMismatches(exec.readOutputRGBA8(), {8, 8}), 0u);
  }
  Executor exec(bindingGraph("lying_unbinder"), reg, *shaders);
  exec.resize({8, 8});
  exec.setStateChecks(true);
  const std::string msg = frameError(exec);
  EXPECT_NE(msg.find("pass 'middle' of type 'lying_unbinder' bound another program (0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("kGlStateBindings"), std::string::npos) << msg;
}

}  // namespace

namespace {

// Binds a buffer of its own at uniform buffer 0, where the scene's Frame block
// is, and answers `declared`.
template <uint32_t declared>
struct FrameBlockHider final : PassInstance {
  void execute(PassContext& ctx) override {
    if (!buffer_) {
      buffer_ = gl::createBuffer();
      glNamedBufferStorage(buffer_.id(), 256, nullptr, 0);
    }
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer_.id());
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{0, 0, 0, 1}.data());
  }
  uint32_t changedState() const override { return declared; }
  gl::Buffer buffer_;
};
// What is bound at uniform buffer 0 when it runs, and what the scene's record says.
uint32_t frameBindingSeen = 0, frameBindingRecorded = 0;
struct FrameBlockLooker final : PassInstance {
  void execute(PassContext& ctx) override {
    GLint b = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &b);
    frameBindingSeen = static_cast<uint32_t>(b);
    frameBindingRecorded = ctx.gpuScene() ? ctx.gpuScene()->recordedFrameBinding() : 0;
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, std::array<float, 4>{1, 1, 1, 1}.data());
  }
  uint32_t changedState() const override { return 0; }
};

// The executor binds the Frame block before a pass only when the scene's
// record says it is not bound there: a pass that binds another buffer at 0
// says so (kGlStateBindings), and the next pass gets the Frame block back;
// one that does not is named by the state checks.
TEST_F(StateTest, BindingsAnotherBufferWhereTheFrameBlockIsMustBeDeclared) {
  ASSERT_TRUE(reg.add(probeType("honest_hider", [] { return std::make_unique<FrameBlockHider<kGlStateBindings>>(); })));
  ASSERT_TRUE(reg.add(probeType("lying_hider", [] { return std::make_unique<FrameBlockHider<0>>(); })));
  ASSERT_TRUE(reg.add(probeType("frame_looker", [] { return std::make_unique<FrameBlockLooker>(); })));
  const Scene scene = loadSceneAny("learnopengl:overview");
  auto hideThenLook = [](const std::string& hider) {
    GraphBuilder g;
    g.texture("a", Format::rgba8).output("out");
    g.pass("hide", hider, {writeUse("dst", Access::color_attachment, "a")});
    g.pass("look", "frame_looker",
           {readUse("src", Access::sampled, "a"), writeUse("dst", Access::color_attachment, "out")});
    return g.config();
  };
  {
    Executor exec(hideThenLook("honest_hider"), reg, *shaders, &scene);
    exec.setStateChecks(true);
    exec.resize({8, 8});
    ASSERT_NO_THROW(exec.renderFrame());
    EXPECT_NE(frameBindingRecorded, 0u);
    EXPECT_EQ(frameBindingSeen, frameBindingRecorded);
  }
  Executor exec(hideThenLook("lying_hider"), reg, *shaders, &scene);
  exec.setStateChecks(true);
  exec.resize({8, 8});
  const std::string msg = frameError(exec);
  EXPECT_NE(msg.find("pass 'hide' of type 'lying_hider' bound another uniform buffer at 0 (the Frame block)"),
            std::string::npos)
      << msg;
}

}  // namespace
