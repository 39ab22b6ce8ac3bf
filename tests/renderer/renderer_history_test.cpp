// History resources through the public renderer: Renderer::cameraCut, a new
// size, a reload and a new scene each start the history again (cleared,
// invalid), as the executor's own first frame does. The pipeline shows its history in the
// output (history_passes.h: a colour per frame, and a probe of its history).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "history_passes.h"
#include "rgraph/gl/executor.h"
#include "rgraph/registry.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;
using rgraph::test::frameColour;
using rgraph::test::historyProbeLog;

const char* kHistoryPipeline = R"({
  "version": 1,
  "resources": {
    "x":      { "format": "rgba8", "size": "output" },
    "x_prev": { "history_of": "x" },
    "out":    { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "colour", "type": "history_test_colour", "outputs": { "color": "x" } },
    { "name": "probe", "type": "history_test_probe", "inputs": { "prev": "x_prev" }, "outputs": { "dst": "out" } }
  ],
  "output": "out"
})";

// Pixels of the output that are not `want` (rgba8 of a frameColour, or zero).
size_t countNot(const std::vector<uint8_t>& rgba, std::array<float, 4> want) {
  size_t bad = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4)
    for (size_t c = 0; c < 4; ++c)
      if (rgba[i + c] != static_cast<uint8_t>(std::lround(want[c] * 255.0f))) {
        ++bad;
        break;
      }
  return bad;
}

constexpr std::array<float, 4> kZero{0.0f, 0.0f, 0.0f, 0.0f};

class RendererHistory : public ::testing::Test {
 protected:
  void SetUp() override {
    testsupport::sharedGlContext();
    // The test's pass types, in-process: the renderer's own registry (a copy of the built-ins with them).
    PassRegistry types = PassRegistry::builtins();
    test::addHistoryTestTypes(types);
    RendererOptions options;
    options.registry = &types;  // copied by the factory
    options.size = {8, 4};
    Diagnostics diags;
    renderer = Renderer::fromJson(kHistoryPipeline, "history.json", options, diags);
    ASSERT_TRUE(renderer) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
    historyProbeLog().clear();
  }

  // Renders a frame; whether its probe saw a valid history and what it showed.
  bool frame(std::array<float, 4> wantShown) {
    renderer->render();
    const std::vector<uint8_t> out = renderer->readOutputRGBA8();
    EXPECT_EQ(countNot(out, wantShown), 0u)
        << "first pixel " << int(out[0]) << "," << int(out[1]) << "," << int(out[2]) << "," << int(out[3]);
    return !historyProbeLog().empty() && historyProbeLog().back().prevValid;
  }

  std::unique_ptr<Renderer> renderer;
};

}  // namespace

TEST_F(RendererHistory, HistoryStartsAgainAfterCameraCutSizeReloadAndScene) {
  renderer->cameraCut();  // before any frame: nothing to cut
  EXPECT_FALSE(frame(kZero));
  EXPECT_TRUE(frame(frameColour(0)));
  EXPECT_TRUE(frame(frameColour(1)));
  renderer->cameraCut();
  EXPECT_FALSE(frame(kZero)) << "after Renderer::cameraCut";
  EXPECT_TRUE(frame(frameColour(3)));

  renderer->setSize({6, 4});
  EXPECT_FALSE(frame(kZero)) << "after Renderer::setSize";
  EXPECT_TRUE(frame(frameColour(0))) << "a new executor counts frames from 0";

  Diagnostics diags;
  ASSERT_TRUE(renderer->reloadJson(kHistoryPipeline, diags));
  EXPECT_FALSE(frame(kZero)) << "after a reload";
  EXPECT_TRUE(frame(frameColour(0)));
  ASSERT_NE(renderer->executor(), nullptr);
  EXPECT_EQ(renderer->executor()->frameIndex(), 2u);

  renderer->setScene(RenderScene::load("learnopengl"));
  EXPECT_FALSE(frame(kZero)) << "after Renderer::setScene";
  EXPECT_TRUE(frame(frameColour(0)));
}
