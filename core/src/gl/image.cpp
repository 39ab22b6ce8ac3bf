#include "rgraph/image.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string_view>

#include "rgraph/error.h"
#include "rgraph/output_file.h"

// Private copy of the writer: static functions, so no clash with another stb user.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace rgraph {

void writePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgba) {
  if (w == 0 || h == 0 || w > INT_MAX / 4 || h > INT_MAX)
    throw RuntimeError("cannot write " + path + ": invalid image size " + std::to_string(w) + "x" + std::to_string(h));
  if (rgba.size() != static_cast<size_t>(w) * h * 4)
    throw RuntimeError("cannot write " + path + ": expected " + std::to_string(static_cast<size_t>(w) * h * 4) +
                       " bytes of RGBA8 pixels, got " + std::to_string(rgba.size()));
  // Encoded in memory, then written by writeOutputFile: stb's own file writer
  // ignores failed writes (a full disk gave a truncated PNG and no error).
  int size = 0;
  unsigned char* png =
      stbi_write_png_to_mem(rgba.data(), static_cast<int>(w * 4), static_cast<int>(w), static_cast<int>(h), 4, &size);
  if (!png) throw RuntimeError("cannot write PNG file " + path + ": out of memory encoding it");
  const std::unique_ptr<unsigned char, void (*)(void*)> owned(png, std::free);
  writeOutputFile(path, std::string_view(reinterpret_cast<const char*>(png), static_cast<size_t>(size)), "PNG file");
}

size_t ImageDifference::pixelsOver(int tolerance) const {
  size_t n = 0;
  for (size_t d = static_cast<size_t>(std::max(tolerance + 1, 0)); d < pixelsByWorst.size(); ++d) n += pixelsByWorst[d];
  return n;
}

double ImageDifference::psnr(double cap) const {
  return mse > 0.0 ? std::min(cap, 10.0 * std::log10(255.0 * 255.0 / mse)) : cap;
}

ImageDifference compareRGBA8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size() || a.size() % 4 != 0)
    throw RuntimeError("cannot compare images of " + std::to_string(a.size()) + " and " + std::to_string(b.size()) +
                       " bytes (RGBA8 images of one size expected)");
  ImageDifference d;
  d.pixels = a.size() / 4;
  double sq = 0.0;
  for (size_t p = 0; p < d.pixels; ++p) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a[p * 4 + c]) - int(b[p * 4 + c]));
      worst = std::max(worst, diff);
      sq += double(diff) * diff;
    }
    ++d.pixelsByWorst[static_cast<size_t>(worst)];
    if (worst > d.maxAbs) d.maxAbs = worst, d.worstPixel = p;
  }
  d.mse = d.pixels ? sq / double(d.pixels * 3) : 0.0;
  return d;
}

}  // namespace rgraph
