// The aa axis's reference filter, edge mask and PSNR (bench_aa_metrics.h).
#include "bench_aa_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "rgraph/error.h"

namespace rgraph::cli::bench {

std::vector<uint8_t> boxDownsample(const std::vector<uint8_t>& rgba, int width, int height, int factor) {
  const size_t bigW = size_t(width) * size_t(factor), bigH = size_t(height) * size_t(factor);
  if (factor < 1 || width < 1 || height < 1 || rgba.size() != bigW * bigH * 4)
    throw RuntimeError("box filter: expected " + std::to_string(bigW) + "x" + std::to_string(bigH) +
                       " RGBA8 pixels, got " + std::to_string(rgba.size()) + " bytes");
  const unsigned n = unsigned(factor * factor);
  std::vector<uint8_t> out(size_t(width) * size_t(height) * 4);
  for (size_t y = 0; y < size_t(height); ++y)
    for (size_t x = 0; x < size_t(width); ++x)
      for (size_t c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (size_t dy = 0; dy < size_t(factor); ++dy)
          for (size_t dx = 0; dx < size_t(factor); ++dx)
            sum += rgba[((y * factor + dy) * bigW + x * factor + dx) * 4 + c];
        out[(y * width + x) * 4 + c] = uint8_t((sum + n / 2) / n);
      }
  return out;
}

namespace {
int luma(const uint8_t* p) { return (299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000; }
}  // namespace

std::vector<uint8_t> edgeMask(const std::vector<uint8_t>& rgba, int width, int height, int threshold) {
  if (width < 1 || height < 1 || rgba.size() != size_t(width) * size_t(height) * 4)
    throw RuntimeError("edge mask: the image is not " + std::to_string(width) + "x" + std::to_string(height) +
                       " RGBA8");
  std::vector<int> l(size_t(width) * size_t(height));
  for (size_t i = 0; i < l.size(); ++i) l[i] = luma(&rgba[i * 4]);
  std::vector<uint8_t> mask(l.size(), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int here = l[size_t(y) * width + x];
      int step = 0;
      if (x > 0) step = std::max(step, std::abs(here - l[size_t(y) * width + x - 1]));
      if (x + 1 < width) step = std::max(step, std::abs(here - l[size_t(y) * width + x + 1]));
      if (y > 0) step = std::max(step, std::abs(here - l[size_t(y - 1) * width + x]));
      if (y + 1 < height) step = std::max(step, std::abs(here - l[size_t(y + 1) * width + x]));
      mask[size_t(y) * width + x] = step >= threshold;
    }
  return mask;
}

double psnrRgb(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference,
               const std::vector<uint8_t>& mask, double cap) {
  if (image.size() != reference.size() || image.size() % 4 != 0 || (!mask.empty() && mask.size() * 4 != image.size()))
    throw RuntimeError("PSNR: image sizes differ (" + std::to_string(image.size()) + " and " +
                       std::to_string(reference.size()) + " bytes, mask " + std::to_string(mask.size()) + ")");
  double sum = 0.0;
  size_t pixels = 0;
  for (size_t i = 0; i * 4 < image.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++pixels;
    for (size_t c = 0; c < 3; ++c) {
      const double d = double(image[i * 4 + c]) - double(reference[i * 4 + c]);
      sum += d * d;
    }
  }
  if (pixels == 0) return std::numeric_limits<double>::quiet_NaN();
  const double mse = sum / double(pixels * 3);
  if (mse <= 0.0) return cap;
  return std::min(cap, 10.0 * std::log10(255.0 * 255.0 / mse));
}

AaError aaError(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, int width, int height,
                double cap) {
  AaError e;
  const std::vector<uint8_t> mask = edgeMask(reference, width, height);
  for (uint8_t m : mask) e.edgePixels += m;
  e.psnr = psnrRgb(image, reference, {}, cap);
  e.edgePsnr = psnrRgb(image, reference, mask, cap);
  return e;
}

}  // namespace rgraph::cli::bench
