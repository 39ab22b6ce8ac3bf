// What the output image reads back as: a one-channel output (a mask, an
// occlusion term) is grey, not the (r, 0, 0, 1) GL reads it as; what
// `rgraph render` writes to PNG is this readback.
#include <gtest/gtest.h>

#include <string>

#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;

std::string clearInto(const std::string& format) {
  return R"({
    "version": 1,
    "resources": { "out": { "format": ")" + format + R"(", "size": "output" } },
    "passes": [ { "name": "fill", "type": "clear", "params": { "color": [0.6, 0.2, 0.9, 1] },
                  "outputs": { "color": "out" } } ],
    "output": "out"
  })";
}

std::vector<uint8_t> renderOnce(const std::string& format) {
  testsupport::sharedGlContext();
  RendererOptions options;
  options.size = {4, 2};
  Diagnostics diags;
  auto renderer = Renderer::fromJson(clearInto(format), format + ".json", options, diags);
  EXPECT_TRUE(renderer) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
  if (!renderer) return {};
  renderer->render();
  return renderer->readOutputRGBA8();
}

}  // namespace

TEST(RendererOutput, OneChannelOutputsReadBackGrey) {
  for (const char* format : {"r8", "r16f", "r32f"}) {
    SCOPED_TRACE(format);
    const std::vector<uint8_t> rgba = renderOnce(format);
    ASSERT_EQ(rgba.size(), 4u * 2u * 4u);
    for (size_t i = 0; i < rgba.size(); i += 4) {
      EXPECT_NEAR(rgba[i], 153, 1);  // 0.6
      EXPECT_EQ(rgba[i + 1], rgba[i]);
      EXPECT_EQ(rgba[i + 2], rgba[i]);
      EXPECT_EQ(rgba[i + 3], 255);
    }
  }
}

TEST(RendererOutput, ColourOutputsKeepTheirChannels) {
  // Two- and four-channel outputs are what they hold (no grey conversion).
  const std::vector<uint8_t> rgba = renderOnce("rgba8");
  ASSERT_EQ(rgba.size(), 32u);
  EXPECT_NEAR(rgba[0], 153, 1);
  EXPECT_NEAR(rgba[1], 51, 1);
  EXPECT_NEAR(rgba[2], 230, 1);
  const std::vector<uint8_t> rg = renderOnce("rg8");
  ASSERT_EQ(rg.size(), 32u);
  EXPECT_NEAR(rg[0], 153, 1);
  EXPECT_NEAR(rg[1], 51, 1);
  EXPECT_EQ(rg[2], 0);
}
