// bloom_blur's "mip_chain" method (bloom.cpp declares the type): the source
// downsampled level by level into the atlas its 'temp' slot holds
// (bloom_chain_layout.h), then upsampled back level by level, each level
// adding its own blur width, and the sum written into 'dst'.
#pragma once

#include <memory>

#include "rgraph/pass.h"

namespace rgraph::bloom {

constexpr int kMaxLevels = 12;
std::unique_ptr<PassInstance> createChainBlur();

}  // namespace rgraph::bloom
