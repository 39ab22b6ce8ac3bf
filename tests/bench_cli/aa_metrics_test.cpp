// The aa axis's maths (apps/rgraph/bench_aa_metrics.h) on synthetic images:
// the box filter that makes the 16-sample reference, the edge mask, PSNR.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "../../apps/rgraph/bench_aa_metrics.h"
#include "rgraph/error.h"
#include "rgraph/image.h"

using namespace rgraph::cli::bench;

namespace {

std::vector<uint8_t> solid(int w, int h, uint8_t v) {
  std::vector<uint8_t> im(size_t(w) * size_t(h) * 4, v);
  for (size_t i = 3; i < im.size(); i += 4) im[i] = 255;
  return im;
}

// Black left of column `edge`, white from it on.
std::vector<uint8_t> step(int w, int h, int edge) {
  std::vector<uint8_t> im = solid(w, h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = edge; x < w; ++x)
      for (int c = 0; c < 3; ++c) im[(size_t(y) * w + x) * 4 + c] = 255;
  return im;
}

}  // namespace

TEST(AaMetrics, BoxDownsampleAveragesEachBlockAndRounds) {
  // 8x4 at factor 4 -> 2x1. Left block: 15 pixels of 0 and one of 255 -> 15.94 -> 16.
  std::vector<uint8_t> big = solid(8, 4, 0);
  for (int c = 0; c < 3; ++c) big[(0 * 8 + 0) * 4 + c] = 255;
  // Right block: a vertical step inside it, 1 of 4 columns white -> 63.75 -> 64.
  for (int y = 0; y < 4; ++y)
    for (int c = 0; c < 3; ++c) big[(size_t(y) * 8 + 7) * 4 + c] = 255;
  const std::vector<uint8_t> small = boxDownsample(big, 2, 1, 4);
  ASSERT_EQ(small.size(), 8u);
  EXPECT_EQ(small[0], 16);
  EXPECT_EQ(small[2], 16);
  EXPECT_EQ(small[3], 255);  // alpha averaged too
  EXPECT_EQ(small[4], 64);
  EXPECT_EQ(small[6], 64);
  // A step on a block boundary survives exactly.
  EXPECT_EQ(boxDownsample(step(16, 4, 8), 4, 1, 4), step(4, 1, 2));
  EXPECT_THROW(boxDownsample(big, 3, 1, 4), rgraph::RuntimeError);
}

TEST(AaMetrics, PsnrHasKnownValues) {
  const auto a = solid(4, 4, 100);
  // Identical: the cap.
  EXPECT_EQ(psnrRgb(a, a, {}, 100.0), 100.0);
  // Off by 1 everywhere: 10 log10(255^2) = 48.13 dB.
  EXPECT_NEAR(psnrRgb(solid(4, 4, 101), a, {}, 100.0), 48.1308, 1e-3);
  // Off by 16: 48.13 - 20 log10(16) = 24.05 dB.
  EXPECT_NEAR(psnrRgb(solid(4, 4, 116), a, {}, 100.0), 24.0484, 1e-3);
  // Black against white: 0 dB.
  EXPECT_NEAR(psnrRgb(solid(4, 4, 0), solid(4, 4, 255), {}, 100.0), 0.0, 1e-9);
  // One pixel of 16 off by 255 in one channel: MSE = 255^2 / 48 -> 10 log10(48).
  auto one = a;
  one[0] = uint8_t(100 + 155);  // off by 155 in R
  EXPECT_NEAR(psnrRgb(one, a, {}, 100.0), 10 * std::log10(255.0 * 255.0 * 48.0 / (155.0 * 155.0)), 1e-9);
  // The same as the library's whole-image PSNR (rgraph/image.h) that the bench's psnr_db uses.
  EXPECT_NEAR(psnrRgb(one, a, {}, 100.0), rgraph::compareRGBA8(one, a).psnr(100.0), 1e-9);
  // Masked to that pixel: 10 log10(255^2 * 3 / 155^2); masked elsewhere: the cap.
  std::vector<uint8_t> mask(16, 0);
  mask[0] = 1;
  EXPECT_NEAR(psnrRgb(one, a, mask, 100.0), 10 * std::log10(255.0 * 255.0 * 3.0 / (155.0 * 155.0)), 1e-9);
  mask[0] = 0;
  mask[5] = 1;
  EXPECT_EQ(psnrRgb(one, a, mask, 100.0), 100.0);
  // No pixel selected: not a number (the bench reports it as a failure).
  EXPECT_TRUE(std::isnan(psnrRgb(one, a, std::vector<uint8_t>(16, 0), 100.0)));
  EXPECT_THROW(psnrRgb(solid(2, 2, 0), a, {}, 100.0), rgraph::RuntimeError);
}

TEST(AaMetrics, EdgeMaskMarksBothSidesOfAStepOnly) {
  const int w = 8, h = 3;
  const auto im = step(w, h, 5);
  const auto mask = edgeMask(im, w, h);
  ASSERT_EQ(mask.size(), size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_EQ(mask[size_t(y) * w + x], (x == 4 || x == 5) ? 1 : 0) << x << "," << y;
  // A step just under the threshold is no edge; at it, it is.
  auto soft = solid(w, h, 100);
  for (int y = 0; y < h; ++y)
    for (int x = 5; x < w; ++x)
      for (int c = 0; c < 3; ++c) soft[(size_t(y) * w + x) * 4 + c] = uint8_t(100 + kEdgeThreshold - 1);
  for (uint8_t m : edgeMask(soft, w, h)) EXPECT_EQ(m, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 5; x < w; ++x)
      for (int c = 0; c < 3; ++c) soft[(size_t(y) * w + x) * 4 + c] = uint8_t(100 + kEdgeThreshold);
  EXPECT_EQ(edgeMask(soft, w, h)[4], 1);
  // A flat image has no edges.
  for (uint8_t m : edgeMask(solid(w, h, 77), w, h)) EXPECT_EQ(m, 0);
}

TEST(AaMetrics, AaErrorScoresTheReferenceAgainstItselfAtTheCapAndBlackLow) {
  const int w = 16, h = 8;
  const auto ref = step(w, h, 7);
  const AaError same = aaError(ref, ref, w, h, 100.0);
  EXPECT_EQ(same.psnr, 100.0);
  EXPECT_EQ(same.edgePsnr, 100.0);
  EXPECT_EQ(same.edgePixels, size_t(2 * h));
  const AaError black = aaError(solid(w, h, 0), ref, w, h, 100.0);
  EXPECT_LT(black.psnr, 5.0);      // half the image off by 255: 3 dB
  EXPECT_LT(black.edgePsnr, 5.0);  // half the edge pixels off by 255
  // An aliased edge (the step one pixel off) scores far below the cap on
  // edges, and better on the whole image, where most pixels agree.
  const AaError shifted = aaError(step(w, h, 8), ref, w, h, 100.0);
  EXPECT_LT(shifted.edgePsnr, 10.0);
  EXPECT_GT(shifted.psnr, shifted.edgePsnr + 5.0);
}
