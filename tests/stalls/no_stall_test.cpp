// A steady-state frame never waits for the GPU (issue 26): with GL timer
// queries (forced here, as llvmpipe would otherwise time on the CPU clock) no
// glFinish, read-back, map or fence wait is made, and every query result is
// read only after GL_QUERY_RESULT_AVAILABLE said it is in; the times still
// arrive, frames later, naming the frame they are of. The CPU clock of
// software renderers is unchanged: the frame just rendered, every pass timed.
// gl_wait_log.h sees librgraph's GL calls as well as this program's.
#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>

#include "gl/gl_test_util.h"  // GraphBuilder (header only)
#include "gl_wait_log.h"
#include "history_passes.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/registry.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;
using stalltest::GlWaits;
using Clock = std::chrono::steady_clock;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";

std::unique_ptr<Renderer> makeRenderer(bool gpuTimerQueries) {
  testsupport::sharedGlContext();
  RendererOptions options;
  options.size = {96, 64};
  options.gpuTimerQueries = gpuTimerQueries;
  Diagnostics diags;
  auto r = Renderer::fromFile(kDefault, options, diags);
  EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  if (r) r->setScene(RenderScene::load("learnopengl:overview"));
  return r;
}

std::string listed(const GlWaits& w) {
  std::string s;
  for (const auto& [name, n] : w.blocking) s += " " + name + " x" + std::to_string(n);
  for (const auto& line : w.unavailableReads) s += "\n  " + line;
  return s;
}

double sumMs(const Renderer& r) {
  double total = 0.0;
  for (const auto& t : r.timings()) total += t.ms;
  return total;
}

// Renders `frames` frames; checks the timings of each steady frame against
// when it began (its passes cannot take longer than the time since then).
// Frames before `steadyFrom` are not checked: llvmpipe's very first query
// can read as hours (a start time it never took).
struct FrameRun {
  std::map<uint64_t, Clock::time_point> began;  // by Renderer::frameIndex()
  std::map<uint64_t, double> sums;              // each steady frame's times seen (by the frame they name)
  size_t passesTimedAboveZero = 0;
  uint64_t steadyFrom = 0;

  void render(Renderer& r, int frames) {
    for (int i = 0; i < frames; ++i) {
      const uint64_t frame = r.frameIndex();
      began[frame] = Clock::now();
      r.render();
      ASSERT_EQ(r.frameIndex(), frame + 1);
      take(r, frame);
    }
  }
  void take(const Renderer& r, uint64_t justRendered) {
    const std::optional<uint64_t> of = r.timingsFrame();
    if (!of) return;
    ASSERT_LE(*of, justRendered);
    ASSERT_TRUE(began.count(*of)) << "timings of frame " << *of << ", which this run did not render";
    if (*of < steadyFrom) return;
    const double elapsedMs = std::chrono::duration<double, std::milli>(Clock::now() - began[*of]).count();
    EXPECT_LE(sumMs(r), elapsedMs) << "frame " << *of << "'s passes add up to more than the time since it began";
    if (!sums.count(*of))
      for (const auto& t : r.timings()) passesTimedAboveZero += t.ms > 0.0;
    sums[*of] = sumMs(r);
  }
};

TEST(NoStall, SteadyFramesWithTimerQueriesNeverWaitForTheGpu) {
  auto r = makeRenderer(/*gpuTimerQueries=*/true);
  ASSERT_TRUE(r);
  FrameRun run;
  run.steadyFrom = r->frameIndex() + 2;
  run.render(*r, 2);  // the build and the first use of everything
  ASSERT_FALSE(r->cpuTimed());
  stalltest::resetWaits();
  run.render(*r, 16);
  const GlWaits w = stalltest::waits();
  EXPECT_TRUE(w.blocking.empty() && w.unavailableReads.empty()) << "a steady frame waited for the GPU:" << listed(w);
  // Whole frames are timed or not (a frame finding the ring's 3 slots in flight is not).
  const size_t passes = r->timings().size();
  EXPECT_EQ(w.queriesBegun % passes, 0u);
  EXPECT_GE(w.queriesBegun, 8 * passes) << "fewer than half the frames timed";
  EXPECT_GT(w.resultReads, 0u) << "no query result was read in 16 frames";
  EXPECT_GT(w.availabilityChecks, 0u);

  // The times arrived, frames after the frame they are of, for several frames.
  ASSERT_TRUE(r->timingsFrame());
  EXPECT_LT(*r->timingsFrame(), r->frameIndex() - 1) << "a query read in the frame that issued it";
  EXPECT_GE(run.sums.size(), 8u) << "fewer than half the steady frames' times came in";
  EXPECT_GT(run.passesTimedAboveZero, 0u);
  for (const auto& [frame, sum] : run.sums) EXPECT_GT(sum, 0.0) << "frame " << frame;

  // What waits when asked to: the read-back (seen here, so the log sees librgraph's calls).
  stalltest::resetWaits();
  (void)r->readOutputRGBA8();
  EXPECT_EQ(stalltest::waits().blocking.count("glGetTextureImage"), 1u) << listed(stalltest::waits());
  // And collectTimings(wait): one glFinish, then the last frame's times, read once they are in
  // (after a first one, the ring is empty: the next frame is surely timed).
  r->collectTimings(/*wait=*/true);
  r->render();
  stalltest::resetWaits();
  r->collectTimings(/*wait=*/true);
  EXPECT_EQ(stalltest::waits().blocking.at("glFinish"), 1u);
  EXPECT_TRUE(stalltest::waits().unavailableReads.empty()) << listed(stalltest::waits());
  EXPECT_EQ(r->timingsFrame(), r->frameIndex() - 1);
  EXPECT_GT(sumMs(*r), 0.0);
}

// Picking (Renderer::requestPick): a pick every frame copies one pixel into a
// pixel pack buffer with a fence, and the answers come in frames later from a
// persistently mapped buffer: no glFinish, no read-back into client memory,
// no map, no fence wait on the frame path; the buffer is made (and mapped,
// once) by the first pick.
TEST(NoStall, PicksEveryFrameNeverWaitForTheGpu) {
  testsupport::sharedGlContext();
  RendererOptions options;
  options.size = {96, 64};
  options.picking = true;
  Diagnostics diags;
  auto r = Renderer::fromFile(kDefault, options, diags);
  ASSERT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  r->setScene(RenderScene::load("learnopengl:overview"));
  r->setCpuPassTiming(false);  // CPU pass timing waits with glFinish by design
  r->requestPick(48, 40);
  r->render();
  r->render();
  stalltest::resetWaits();
  for (uint32_t i = 0; i < 12; ++i) {
    r->requestPick(40 + i, 40);
    r->render();
    (void)r->pickResult();  // nullopt here: each request replaces the one before
  }
  r->render();
  (void)r->pickResult();
  const GlWaits w = stalltest::waits();
  EXPECT_TRUE(w.blocking.empty()) << "a frame with a pick waited for the GPU:" << listed(w);
  EXPECT_GE(w.packBufferReads, 6u) << "fewer picks copied than half the frames";
  // The last request was copied by its frame; its answer comes in (waited for here, off the frame path).
  const std::optional<PickResult> last = r->pickResult(/*wait=*/true);
  ASSERT_TRUE(last);
  EXPECT_EQ(last->x, 51u);
  EXPECT_TRUE(last->problem.empty()) << last->problem;
}

// A rebuild (here a new size) drops the queries in flight: no frame's times
// are reported until one rendered since is in, and none names an earlier frame.
TEST(NoStall, ARebuildAttributesNoTimesAcrossIt) {
  auto r = makeRenderer(/*gpuTimerQueries=*/true);
  ASSERT_TRUE(r);
  FrameRun run;
  run.steadyFrom = UINT64_MAX;  // attribution only (the sums: the test above)
  run.render(*r, 6);
  ASSERT_TRUE(r->timingsFrame());
  const uint64_t rebuiltAt = r->frameIndex();
  r->setSize({48, 32});
  run.render(*r, 1);
  EXPECT_FALSE(r->timingsFrame()) << "frame " << *r->timingsFrame() << "'s times survived the rebuild";
  run.render(*r, 8);
  ASSERT_TRUE(r->timingsFrame());
  EXPECT_GE(*r->timingsFrame(), rebuiltAt);

  // The executor's own resize: the same.
  Executor& exec = *r->executor();
  exec.collectTimings(/*wait=*/true);
  ASSERT_TRUE(exec.timingsFrame());
  exec.resize({40, 24});
  EXPECT_FALSE(exec.timingsFrame());
  for (const auto& t : exec.timings()) EXPECT_EQ(t.ms, 0.0) << t.name;
  const uint64_t resizedAt = exec.frameIndex();
  exec.renderFrame();
  exec.collectTimings(/*wait=*/true);
  EXPECT_EQ(exec.timingsFrame(), resizedAt);
}

// A pass type that draws nothing and throws the third time it runs.
class ThrowsOnce final : public PassInstance {
 public:
  void execute(PassContext&) override {
    if (++runs_ == 3) throw RuntimeError("the third frame fails on purpose");
  }

 private:
  int runs_ = 0;
};

// A frame that throws half-way leaves its queries begun and ended in pairs
// (no GL error after), and the frames after it are timed.
TEST(NoStall, AFrameThatThrowsLeavesTheQueriesBalancedAndTimesKeepComing) {
  GlContext& context = testsupport::sharedGlContext();
  PassRegistry reg = PassRegistry::builtins();
  test::addHistoryTestTypes(reg);
  if (!reg.find("stall_test_throw")) {
    PassTypeDesc t;
    t.name = "stall_test_throw";
    t.description = "test: throws the third time it runs";
    t.slots = {test::history_detail::slot("color", Access::color_attachment)};
    t.create = [] { return std::make_unique<ThrowsOnce>(); };
    reg.add(std::move(t));
  }
  test::GraphBuilder g;
  g.texture("x", Format::rgba8).texture("y", Format::rgba8).output("out");
  g.pass("colour", "history_test_colour", {test::writeUse("color", Access::color_attachment, "x")});
  g.pass("throws", "stall_test_throw", {test::writeUse("color", Access::color_attachment, "y")}, {}, true);
  g.pass("present", "present",
         {test::readUse("src", Access::sampled, "x"), test::writeUse("dst", Access::color_attachment, "out")});
  ShaderLibrary shaders;
  Executor exec(g.config(), reg, shaders);
  exec.setGpuTimerQueries(true);
  exec.resize({16, 8});
  const uint64_t errorsBefore = context.debugErrorCount();
  stalltest::resetWaits();
  std::vector<uint64_t> reported;  // the frames timings were of, each once
  for (int call = 0; call < 9; ++call) {
    if (call == 2)
      EXPECT_THROW(exec.renderFrame(), RuntimeError);
    else
      exec.renderFrame();
    if (exec.timingsFrame() && (reported.empty() || reported.back() != *exec.timingsFrame()))
      reported.push_back(*exec.timingsFrame());
  }
  exec.collectTimings(/*wait=*/true);
  reported.push_back(*exec.timingsFrame());
  EXPECT_EQ(context.debugErrorCount(), errorsBefore) << "a GL error: a query left begun, or ended twice";
  EXPECT_TRUE(stalltest::waits().unavailableReads.empty()) << listed(stalltest::waits());
  // frameIndex counts the frames that completed (8): the one that threw is
  // none, and the frame after it ran as frame 2. Times keep coming, in order.
  EXPECT_EQ(exec.frameIndex(), 8u);
  EXPECT_EQ(reported.back(), exec.frameIndex() - 1);
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  EXPECT_GE(reported.size(), 3u);
}

// Software renderers keep the CPU clock (a glFinish after each pass, asked
// for): the frame just rendered, every pass timed, adding up to no more than
// the frame's own wall time.
TEST(NoStall, CpuTimingsOnSoftwareRenderersAreOfTheFrameJustRendered) {
  auto r = makeRenderer(/*gpuTimerQueries=*/false);
  ASSERT_TRUE(r);
  r->render();
  if (!r->cpuTimed()) {  // a GPU: queries by default, never the frame just rendered, never a wait
    stalltest::resetWaits();
    for (int i = 0; i < 4; ++i) {
      r->render();
      if (r->timingsFrame()) EXPECT_LT(*r->timingsFrame(), r->frameIndex() - 1);
    }
    EXPECT_TRUE(stalltest::waits().blocking.empty() && stalltest::waits().unavailableReads.empty())
        << listed(stalltest::waits());
    return;
  }
  for (int i = 0; i < 3; ++i) {
    stalltest::resetWaits();
    const auto t0 = Clock::now();
    r->render();
    const double wallMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    ASSERT_EQ(r->timingsFrame(), r->frameIndex() - 1);
    ASSERT_FALSE(r->timings().empty());
    for (const auto& t : r->timings()) EXPECT_GT(t.ms, 0.0) << t.name;
    EXPECT_LE(sumMs(*r), wallMs);
    const GlWaits w = stalltest::waits();
    EXPECT_EQ(w.blocking.at("glFinish"), r->timings().size() + 1) << "one before the first pass, one after each";
    EXPECT_EQ(w.queriesBegun, 0u);
  }
  r->setCpuPassTiming(false);
  stalltest::resetWaits();
  r->render();
  EXPECT_FALSE(r->timingsFrame());
  EXPECT_TRUE(stalltest::waits().blocking.empty()) << listed(stalltest::waits());
}

}  // namespace
