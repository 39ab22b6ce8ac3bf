// bloom_blur's "mip_chain" method (bloom.cpp declares the type): the source
// downsampled level by level into the mip levels of its 'temp' slot (mip
// level k - 1 of temp holds the chain's level k, half the one before rounded
// up, at its origin), then upsampled back level by level, each level adding
// its own blur width, and the sum written into 'dst'.
#pragma once

#include <memory>

#include "rgraph/pass.h"

namespace rgraph::bloom {

constexpr int kMaxLevels = 12;
std::unique_ptr<PassInstance> createChainBlur();

}  // namespace rgraph::bloom
