// Image files (no GL). Pixels are RGBA8, rows top-down.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rgraph {

// Writes a PNG through writeOutputFile (rgraph/output_file.h: a temporary file
// renamed into place, every write checked). Throws rgraph::RuntimeError naming
// the path when the size of `rgba` is not w*h*4 or the file cannot be written
// ("cannot write PNG file PATH: REASON", the OS's reason).
void writePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgba);

// How two RGBA8 images of the same size differ over RGB (alpha ignored): the
// one comparison behind `rgraph bench`, the render benchmarks and the image
// tests, so that their figures mean the same thing.
struct ImageDifference {
  size_t pixels = 0;
  int maxAbs = 0;         // largest |a - b| over pixels and RGB channels
  size_t worstPixel = 0;  // index of a pixel with that difference
  double mse = 0.0;       // mean squared difference over pixels x 3 channels
  // pixelsByWorst[d]: pixels whose largest channel difference is d.
  std::vector<size_t> pixelsByWorst = std::vector<size_t>(256, 0);

  // Pixels with a channel off by more than `tolerance`.
  size_t pixelsOver(int tolerance) const;
  double shareOver(int tolerance) const { return pixels ? double(pixelsOver(tolerance)) / double(pixels) : 0.0; }
  // 10 log10(255^2 / mse) in dB; `cap` when identical or closer than that.
  double psnr(double cap) const;
};
// Throws rgraph::RuntimeError when the sizes differ or are not a multiple of 4.
ImageDifference compareRGBA8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

}  // namespace rgraph
