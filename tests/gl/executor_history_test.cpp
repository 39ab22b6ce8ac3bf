// History resources in the executor (ResourceDecl::historyOf): after each
// frame the source's texture is copied into the history's; the history is
// cleared to zero and PassContext::historyValid is false on the first frame,
// after a resize and after a camera cut; frameIndex counts every frame.
// A pass writes a different colour each frame (history_passes.h), a probe
// shows what the history holds during the next one.
#include <GL/glcorearb.h>

#include <cmath>

#include "gl_test_util.h"
#include "history_passes.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr Extent kSize{16, 8};
constexpr std::array<float, 4> kZero{0.0f, 0.0f, 0.0f, 0.0f};

// Pixels of an RGBA32F readback that differ from `want` by more than half a
// step of rgba8.
size_t countNot(const std::vector<float>& rgba, std::array<float, 4> want) {
  size_t bad = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4)
    for (size_t c = 0; c < 4; ++c)
      if (std::abs(rgba[i + c] - want[c]) > 0.5f / 255.0f) {
        ++bad;
        break;
      }
  return bad;
}

std::string first(const std::vector<float>& rgba) {
  return rgba.size() < 4 ? std::string("(empty)")
                         : std::to_string(rgba[0]) + "," + std::to_string(rgba[1]) + "," + std::to_string(rgba[2]) +
                               "," + std::to_string(rgba[3]);
}

PassRegistry historyRegistry() {
  PassRegistry reg = PassRegistry::builtins();
  addHistoryTestTypes(reg);
  return reg;
}

void addHistory(GraphBuilder& g, const std::string& name, const std::string& of, uint32_t samples = 1) {
  g.texture(name, Format::rgba8, SizeSpec::output(), std::nullopt, samples);
  g.config().graph.resources.back().historyOf = of;
}

// x (written each frame, presented), x_prev = history of x, shown by the probe
// into `seen` (a side effect).
PipelineConfig shownSourceGraph() {
  GraphBuilder g;
  g.texture("x", Format::rgba8).texture("seen", Format::rgba8).output("out");
  addHistory(g, "x_prev", "x");
  g.pass("colour", "history_test_colour", {writeUse("color", Access::color_attachment, "x")});
  g.pass("probe", "history_test_probe",
         {readUse("prev", Access::sampled, "x_prev"), writeUse("dst", Access::color_attachment, "seen")}, {}, true);
  g.pass("present", "present",
         {readUse("src", Access::sampled, "x"), writeUse("dst", Access::color_attachment, "out")});
  return g.config();
}

// x is read by nobody in its frame: only its history, in the next one, which
// the probe copies to the output.
PipelineConfig nextFrameOnlyGraph(uint32_t samples = 1) {
  GraphBuilder g;
  g.texture("x", Format::rgba8, SizeSpec::output(), std::nullopt, samples).output("out");
  addHistory(g, "x_prev", "x", samples);
  g.pass("colour", "history_test_colour", {writeUse("color", Access::color_attachment, "x")});
  g.pass("probe", "history_test_probe",
         {readUse("prev", Access::sampled, "x_prev", samples > 1), writeUse("dst", Access::color_attachment, "out")});
  return g.config();
}

std::vector<float> outputFloats(const Executor& exec) {
  std::vector<float> f;
  for (uint8_t b : exec.readOutputRGBA8()) f.push_back(static_cast<float>(b) / 255.0f);
  return f;
}

}  // namespace

TEST_F(GlTest, HistoryHoldsTheSourcesPreviousFrame) {
  const PassRegistry reg = historyRegistry();
  Executor exec(shownSourceGraph(), reg, *shaders);
  exec.resize(kSize);
  const Plan& plan = exec.plan();
  ASSERT_TRUE(plan.ok());
  ASSERT_TRUE(plan.resources[3].historyOf.valid()) << "the compiler linked no history";
  EXPECT_NE(exec.textureOf("x_prev"), exec.textureOf("x"));
  historyProbeLog().clear();
  for (uint64_t n = 0; n < 4; ++n) {
    EXPECT_EQ(exec.frameIndex(), n);
    exec.renderFrame();
    const std::vector<float> seen = exec.readTextureRGBA32F("seen");
    // During frame n the history held frame n-1's colour (zeros on the first).
    const std::array<float, 4> want = n == 0 ? kZero : frameColour(n - 1);
    EXPECT_EQ(countNot(seen, want), 0u) << "frame " << n << ": " << first(seen);
    // After it, frame n's own (the copy after the last pass).
    EXPECT_EQ(countNot(exec.readTextureRGBA32F("x_prev"), frameColour(n)), 0u) << "frame " << n;
  }
  EXPECT_EQ(exec.frameIndex(), 4u);
  ASSERT_EQ(historyProbeLog().size(), 4u);
  for (uint64_t n = 0; n < 4; ++n) {
    EXPECT_EQ(historyProbeLog()[n].frame, n);
    EXPECT_EQ(historyProbeLog()[n].prevValid, n > 0) << "frame " << n;
    EXPECT_FALSE(historyProbeLog()[n].dstValid) << "a slot bound to no history resource is never valid";
  }
}

TEST_F(GlTest, HistoryIsClearedAndInvalidAfterCameraCutAndResize) {
  const PassRegistry reg = historyRegistry();
  Executor exec(shownSourceGraph(), reg, *shaders);
  exec.resize(kSize);
  historyProbeLog().clear();
  exec.renderFrame();
  exec.renderFrame();
  exec.cameraCut();
  exec.renderFrame();  // frame 2: follows no previous one
  std::vector<float> seen = exec.readTextureRGBA32F("seen");
  EXPECT_EQ(countNot(seen, kZero), 0u) << "not cleared after a camera cut: " << first(seen);
  exec.renderFrame();  // frame 3: frame 2's colour again
  seen = exec.readTextureRGBA32F("seen");
  EXPECT_EQ(countNot(seen, frameColour(2)), 0u) << first(seen);

  exec.resize({kSize.width * 2, kSize.height});
  exec.renderFrame();  // frame 4, counted on across the resize
  seen = exec.readTextureRGBA32F("seen");
  EXPECT_EQ(seen.size(), static_cast<size_t>(kSize.width * 2 * kSize.height * 4));
  EXPECT_EQ(countNot(seen, kZero), 0u) << "not cleared after a resize: " << first(seen);
  exec.renderFrame();
  EXPECT_EQ(countNot(exec.readTextureRGBA32F("seen"), frameColour(4)), 0u);

  ASSERT_EQ(historyProbeLog().size(), 6u);
  const bool valid[] = {false, true, false, true, false, true};
  for (size_t n = 0; n < 6; ++n) {
    EXPECT_EQ(historyProbeLog()[n].frame, n);
    EXPECT_EQ(historyProbeLog()[n].prevValid, valid[n]) << "frame " << n;
  }
}

// Culling keeps the writer of a source that only the next frame's history
// read needs, and the executor copies it.
TEST_F(GlTest, HistoryCopiesASourceOnlyTheNextFrameReads) {
  const PassRegistry reg = historyRegistry();
  Executor exec(nextFrameOnlyGraph(), reg, *shaders);
  exec.resize(kSize);
  ASSERT_EQ(exec.plan().order.size(), 2u) << "the pass that only feeds the next frame was culled";
  for (uint64_t n = 0; n < 3; ++n) {
    exec.renderFrame();
    const std::vector<float> out = outputFloats(exec);
    EXPECT_EQ(countNot(out, n == 0 ? kZero : frameColour(n - 1)), 0u) << "frame " << n << ": " << first(out);
  }
}

// A multisampled source keeps a multisampled history, copied sample for sample
// (the probe's blit resolves it).
TEST_F(GlTest, HistoryOfAMultisampledSource) {
  const PassRegistry reg = historyRegistry();
  Executor exec(nextFrameOnlyGraph(4), reg, *shaders);
  exec.resize(kSize);
  historyProbeLog().clear();
  for (uint64_t n = 0; n < 3; ++n) {
    exec.renderFrame();
    const std::vector<float> out = outputFloats(exec);
    EXPECT_EQ(countNot(out, n == 0 ? kZero : frameColour(n - 1)), 0u) << "frame " << n << ": " << first(out);
  }
  ASSERT_EQ(historyProbeLog().size(), 3u);
  EXPECT_FALSE(historyProbeLog()[0].prevValid);
  EXPECT_TRUE(historyProbeLog()[2].prevValid);
}

// A rebuilt pipeline (Executor::reuseTextures) shares transients, never a
// history or its source, and starts without history.
TEST_F(GlTest, HistoryTexturesAreNotSharedWithAReplacingExecutor) {
  const PassRegistry reg = historyRegistry();
  Executor before(shownSourceGraph(), reg, *shaders);
  before.resize(kSize);
  before.renderFrame();
  before.renderFrame();
  Executor after(shownSourceGraph(), reg, *shaders);
  after.reuseTextures(before);
  after.resize(kSize);
  EXPECT_EQ(after.textureOf("seen"), before.textureOf("seen")) << "a transient of the same shape is shared";
  EXPECT_NE(after.textureOf("x"), before.textureOf("x"));
  EXPECT_NE(after.textureOf("x_prev"), before.textureOf("x_prev"));
  EXPECT_NE(after.textureOf("x"), before.textureOf("x_prev"));
  EXPECT_NE(after.textureOf("x_prev"), before.textureOf("x"));
  historyProbeLog().clear();
  after.renderFrame();
  EXPECT_EQ(after.frameIndex(), 1u);
  ASSERT_EQ(historyProbeLog().size(), 1u);
  EXPECT_FALSE(historyProbeLog()[0].prevValid);
  EXPECT_EQ(countNot(after.readTextureRGBA32F("seen"), kZero), 0u);
  // The previous executor's history is its own still: frame 1's colour.
  before.renderFrame();
  EXPECT_EQ(countNot(before.readTextureRGBA32F("seen"), frameColour(1)), 0u);
}
