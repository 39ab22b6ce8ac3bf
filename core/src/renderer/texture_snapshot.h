// What the hazard harness (hazard_check.cpp) compares: every level, layer and
// sample of a texture read back as 32-bit words. Not installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"

namespace rgraph::hazard_detail {

// One level of a texture: per texel `channels` values (RGBA per sample,
// or depth alone for a single-sample depth texture).
struct Level {
  uint32_t width = 0, height = 0, layers = 1, channels = 4;
  uint32_t samples = 1;
  bool integer = false;  // texels hold integer bits, compared exactly
  std::vector<float> texels;
};
using Snapshot = std::vector<Level>;

// Reads textures back; needs a current GL context (the one that made them).
class SnapshotReader {
 public:
  // Every level (all layers and faces) of a single-sample texture; each
  // sample of each texel of a multisampled one (2D or 2D array), fetched one
  // by one (texelFetch) by a compute program: a texel differs when any of its
  // samples does, so a pass that writes one sample wrongly is seen even where
  // a resolve would average it away.
  Snapshot read(uint32_t texture, bool depth);

 private:
  Snapshot readMultisampled(uint32_t texture, unsigned target);
  ShaderLibrary shaders_;  // the built-in shaders (hazard_samples.comp)
  gl::Buffer words_;
  size_t wordCapacity_ = 0;
};

}  // namespace rgraph::hazard_detail
