// Where the bloom mip chain (bloom_blur, method "mip_chain") keeps its levels:
// one texture, the pass's 'temp' slot, holds every level side by side (an
// atlas) rather than one texture per level. Why: 'temp' is then an ordinary
// transient of the chain's source size and format, which the graph aliases
// with any dead target of that descriptor (in deferred-ssao-bloom, a G-buffer
// target dead after lighting), and `rgraph plan` counts its bytes like any
// other resource's. GL-free: the check hook uses it without a context.
//
// Level 1 is half the source (rounded up), each further level half the one
// before. Level 1 sits at the origin; level 2 to its right; every further
// level below the one before it, in level 2's column:
//
//   +---------+----+
//   |         | L2 |
//   |   L1    +----+
//   |         | L3 |
//   |         +----+ ...
//   +---------+
#pragma once

#include <cstdint>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph::bloom {

struct Rect {
  uint32_t x = 0, y = 0, width = 0, height = 0;
};

// The levels' rectangles in 'temp' for a source of size `src`, levels 1..n
// (index 0 is level 1).
std::vector<Rect> chainLayout(Extent src, int levels);
// The smallest 'temp' that holds them.
Extent chainExtent(Extent src, int levels);

}  // namespace rgraph::bloom
