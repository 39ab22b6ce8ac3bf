#include "bloom_chain_layout.h"

#include <algorithm>

namespace rgraph::bloom {

namespace {
uint32_t half(uint32_t v) { return std::max<uint32_t>(1, (v + 1) / 2); }
}  // namespace

std::vector<Rect> chainLayout(Extent src, int levels) {
  std::vector<Rect> rects;
  uint32_t w = src.width, h = src.height, column = 0, below = 0;
  for (int k = 1; k <= levels; ++k) {
    w = half(w), h = half(h);
    Rect r{0, 0, w, h};
    if (k == 2) column = rects[0].width;
    if (k >= 2) r.x = column, r.y = below, below += h;
    rects.push_back(r);
  }
  return rects;
}

Extent chainExtent(Extent src, int levels) {
  Extent e;
  for (const Rect& r : chainLayout(src, levels)) {
    e.width = std::max(e.width, r.x + r.width);
    e.height = std::max(e.height, r.y + r.height);
  }
  return e;
}

}  // namespace rgraph::bloom
