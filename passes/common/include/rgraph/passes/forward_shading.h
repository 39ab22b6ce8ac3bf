// Scene drawing with forward shading, shared by the forward pass (blended
// surfaces over a deferred image) and forward_lit (the whole scene): one
// program per lighting configuration, every point light per fragment.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rgraph/gl/uniform.h"
#include "rgraph/pass.h"

namespace rgraph::forward {

// The forward_lit programs for the pass's lighting and shadow params
// (shadows::declareReader), for PassTypeDesc::programs: without and with
// HAS_NORMAL_MAPS (which one runs follows the scene: lighting::normalMapVariant).
std::vector<ShaderProgramSpec> programs(const ParamSet& params, bool blendsSourceAlpha);

// Draws the scene's surfaces of one kind with a forward_lit program: opaque
// (depth written) or blended (back to front, alpha blending, depth tested but
// not written). Its uniforms are looked up once, at construction (setup).
// With the pass's `clusters` slot bound (cluster_lists.h), each fragment
// shades its cluster's lights only (forward+), else every light.
class SurfaceDrawer {
 public:
  SurfaceDrawer() = default;
  explicit SurfaceDrawer(uint32_t program);
  void draw(PassContext& ctx, bool blended) const;

 private:
  uint32_t program_ = 0;
  gl::Uniform pointLightCount_, blendPass_, clustered_;
};

}  // namespace rgraph::forward
