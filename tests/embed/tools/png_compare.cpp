// rgraph_png_compare A.png B.png TOLERANCE [--region X,Y,W,H] [--exclude X,Y,W,H]... [--scale R,G,B]
// Compares the RGB of two PNGs of the same size (rgraph::compareRGBA8) over
// the pixels inside --region (default: all) and outside every --exclude
// rectangle (x from the left, y from the top); --scale multiplies B's channels
// by R, G, B first, rounding to the nearest byte (B as a pass that multiplies
// its input would make it: the editor example's tint). Prints the largest channel
// difference and where it is. Exit 0: within TOLERANCE; 2: over it; 1: the
// files or arguments are unusable.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/image.h"

namespace {

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
  bool contains(int px, int py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

bool parseScale(const char* text, float s[3]) {
  char tail = 0;
  return std::sscanf(text, "%f,%f,%f%c", &s[0], &s[1], &s[2], &tail) == 3 && s[0] >= 0 && s[1] >= 0 && s[2] >= 0;
}

bool parseRect(const char* text, Rect& r) {
  char tail = 0;
  return std::sscanf(text, "%d,%d,%d,%d%c", &r.x, &r.y, &r.w, &r.h, &tail) == 4 && r.w > 0 && r.h > 0;
}

std::vector<uint8_t> load(const char* path, int& w, int& h) {
  int n = 0;
  unsigned char* px = stbi_load(path, &w, &h, &n, 4);
  if (!px) throw rgraph::RuntimeError(std::string("cannot read ") + path + ": " + stbi_failure_reason());
  std::vector<uint8_t> rgba(px, px + size_t(w) * h * 4);
  stbi_image_free(px);
  return rgba;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s A.png B.png TOLERANCE [--region X,Y,W,H] [--exclude X,Y,W,H]...\n", argv[0]);
    return 1;
  }
  try {
    const int tolerance = std::atoi(argv[3]);
    int w = 0, h = 0, wb = 0, hb = 0;
    const std::vector<uint8_t> a = load(argv[1], w, h);
    std::vector<uint8_t> b = load(argv[2], wb, hb);
    if (w != wb || h != hb)
      throw rgraph::RuntimeError("sizes differ: " + std::to_string(w) + "x" + std::to_string(h) + " and " +
                                 std::to_string(wb) + "x" + std::to_string(hb));
    Rect region{0, 0, w, h};
    std::vector<Rect> excluded;
    float scale[3] = {1, 1, 1};
    for (int i = 4; i < argc; i += 2) {
      const std::string flag = argv[i];
      Rect r;
      if (flag == "--scale" && i + 1 < argc && parseScale(argv[i + 1], scale)) continue;
      if (i + 1 >= argc || (flag != "--region" && flag != "--exclude") || !parseRect(argv[i + 1], r))
        throw rgraph::RuntimeError("bad argument '" + flag + "' (--region X,Y,W,H, --exclude X,Y,W,H or --scale R,G,B)");
      if (flag == "--region")
        region = r;
      else
        excluded.push_back(r);
    }
    for (size_t i = 0; i < b.size(); ++i)
      if (i % 4 != 3) b[i] = uint8_t(std::min(255.0f, std::round(float(b[i]) * scale[i % 4])));
    // Pixels not compared take A's value in B: they add no difference.
    size_t compared = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        bool skip = !region.contains(x, y);
        for (const Rect& r : excluded) skip = skip || r.contains(x, y);
        const size_t i = (size_t(y) * w + x) * 4;
        if (skip)
          std::copy_n(&a[i], 4, &b[i]);
        else
          ++compared;
      }
    if (compared == 0) throw rgraph::RuntimeError("no pixel left to compare");
    const rgraph::ImageDifference d = rgraph::compareRGBA8(a, b);
    const int wx = int(d.worstPixel % size_t(w)), wy = int(d.worstPixel / size_t(w));
    std::printf("max difference %d at %d,%d over %zu pixels compared, %zu over tolerance %d\n", d.maxAbs, wx, wy,
                compared, d.pixelsOver(tolerance), tolerance);
    return d.maxAbs <= tolerance ? 0 : 2;
  } catch (const rgraph::RuntimeError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
