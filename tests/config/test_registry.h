// Fake pass types for the config tests: a private PassRegistry, never builtins().
#pragma once

#include <string>

#include "rgraph/config.h"
#include "rgraph/registry.h"

namespace rgraph::test {

// fullscreen : source (sampled, required), aux (sampled, optional),
//              color (color_attachment, required, Load::optional); param exposure float [0, 10] = 1
// geometry   : color (color_attachment, formats rgba8/rgba16f/srgb8_alpha8, accepts MSAA),
//              depth (depth_attachment, depth formats); both Load::never
// blit       : src (blit_src), dst (blit_dst, Load::optional)
// blend      : color (color_attachment, Load::required), overlay (sampled, optional)
// resolve    : src (sampled, accepts MSAA), dst (color_attachment)
// readback   : src (sampled), side effect
// decal      : color (color_attachment, optional, Load::optional)
// histogram  : image (sampled), bins (storage_write, Load::optional)
// tweak      : color (color_attachment); params of every type:
//              flag bool=false, count int [0,16]=4, gain float [0,10]=1, label string="x",
//              mode enum {fast,nice,exact}=nice, tint vec3 [0,1]=(1,1,1), rect vec4=(0,0,1,1),
//              bias float >= -1 (no max) = 0
const PassRegistry& testRegistry();

// The directory holding tests/configs.
inline std::string configsDir() { return std::string(RGRAPH_TEST_DATA_DIR) + "/configs"; }

std::string readFile(const std::string& path);

}  // namespace rgraph::test
