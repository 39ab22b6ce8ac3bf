// The format sets several pass types share (rgraph/format_sets.h): each holds
// what its name promises and nothing else, so a slot that takes a set
// accepts every such format.
#include <gtest/gtest.h>

#include <algorithm>

#include "rgraph/format_sets.h"

using namespace rgraph;

namespace {

bool contains(const std::vector<Format>& v, Format f) { return std::find(v.begin(), v.end(), f) != v.end(); }

TEST(FormatSets, DepthFormatsAreEveryDepthFormatInDeclarationOrder) {
  EXPECT_EQ(depthFormats(), (std::vector<Format>{Format::depth24, Format::depth32f, Format::depth24_stencil8,
                                                  Format::depth32f_stencil8}));
  for (Format f : allFormats()) EXPECT_EQ(contains(depthFormats(), f), isDepthFormat(f)) << formatName(f);
}

TEST(FormatSets, HdrAndVelocityFormatsAreRenderableFloatColourFormats) {
  EXPECT_EQ(hdrFormats(), (std::vector<Format>{Format::rgba16f, Format::rgba32f, Format::r11g11b10f}));
  EXPECT_EQ(velocityFormats(), (std::vector<Format>{Format::rg16f, Format::rgba16f, Format::rgba32f}));
  for (Format f : hdrFormats()) {
    const FormatInfo& i = formatInfo(f);
    EXPECT_TRUE(i.isFloat && i.colorRenderable && !i.isDepth && i.components >= 3) << i.name;
  }
  for (Format f : velocityFormats()) {
    const FormatInfo& i = formatInfo(f);
    EXPECT_TRUE(i.isFloat && i.colorRenderable && !i.isDepth && i.components >= 2) << i.name;
  }
}

TEST(FormatSets, FormatNameListJoinsWithCommasAndOr) {
  EXPECT_EQ(formatNameList(depthFormats()), "depth24, depth32f, depth24_stencil8 or depth32f_stencil8");
  EXPECT_EQ(formatNameList({Format::rgba8, Format::r8}), "rgba8 or r8");
  EXPECT_EQ(formatNameList({Format::rg16f}), "rg16f");
  EXPECT_EQ(formatNameList({}), "");
}

}  // namespace
