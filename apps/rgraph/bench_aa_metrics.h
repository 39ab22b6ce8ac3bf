// The maths of the bench's aa axis, free of GL so that it is unit-tested on
// synthetic images (tests/bench_cli/aa_metrics_test.cpp):
//
// - the reference: an image rendered at `factor` times the width and height,
//   box-filtered down (factor 4: 16 samples per pixel). The filter averages
//   the stored 8-bit values (after tone mapping, as displayed), rounding to
//   nearest: the error is then measured in the space the methods are seen in.
// - the edge mask: pixels whose luma (Rec. 601 weights, 0..255) differs from a
//   4-neighbour's by at least kEdgeThreshold in the reference: both sides of
//   a strong edge, and thin lines of either polarity.
// - PSNR over RGB, over all pixels or the masked ones, capped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rgraph::cli::bench {

// A luma step of 32/255 between neighbours marks an edge: well above the
// 1-3/255 shading differences between neighbours inside surfaces, and below
// the contrast of the scenes' object silhouettes against their backgrounds.
constexpr int kEdgeThreshold = 32;

// RGBA8 rows of `width * factor` by `height * factor` pixels -> width by
// height, each pixel the rounded mean of its factor x factor block (all four
// channels). Throws RuntimeError when the size does not match.
std::vector<uint8_t> boxDownsample(const std::vector<uint8_t>& rgba, int width, int height, int factor);

// 1 for an edge pixel, 0 elsewhere (width * height entries).
std::vector<uint8_t> edgeMask(const std::vector<uint8_t>& rgba, int width, int height, int threshold = kEdgeThreshold);

// 10 log10(255^2 / MSE) over the RGB channels of the pixels where mask is
// non-zero (every pixel when mask is empty); `cap` when the images agree
// there or closer than that; NaN when no pixel is selected. Throws
// RuntimeError when sizes differ.
double psnrRgb(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference,
               const std::vector<uint8_t>& mask, double cap);

struct AaError {
  double psnr = 0.0;      // dB, whole image
  double edgePsnr = 0.0;  // dB, edge pixels of the reference
  size_t edgePixels = 0;
};
AaError aaError(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, int width, int height,
                double cap);

}  // namespace rgraph::cli::bench
