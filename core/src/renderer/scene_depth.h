// The scene's depth kept for the caller's overlays (Renderer::outputDepthTexture):
// which resource holds it in a plan, and a copy of it taken right after the
// pass that last writes it (later passes may alias its texture, so the end
// of the frame is too late to read it in place).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "rgraph/gl/objects.h"
#include "rgraph/graph.h"

namespace rgraph {

class Executor;
class PassRegistry;

// Where a plan's scene depth is: the resource and the step after which it is
// complete. `wanted` names the resource (RendererOptions::depthResource);
// empty: the last depth attachment at the output's size, one layer, of a pass
// whose type draws the scene (PassTypeDesc::needsScene). nullopt when there
// is none (or `wanted` is not attached as depth by any pass that runs).
struct SceneDepthSource {
  std::string resource;
  size_t step = 0;
};
std::optional<SceneDepthSource> findSceneDepth(const Plan& plan, const PassRegistry& registry,
                                               const std::string& wanted);

class SceneDepthCopy {
 public:
  // Where the next frames' depth comes from (findSceneDepth of the executor's
  // plan); nullopt: none, and the texture is given back.
  void setSource(std::optional<SceneDepthSource> source);
  // After each pass: at the source's step, copies its texture (a blit, which
  // resolves a multisampled depth) into this object's texture.
  void afterPass(size_t step, const Executor& executor);
  bool active() const { return source_.has_value(); }
  const std::optional<SceneDepthSource>& source() const { return source_; }
  uint32_t texture() const { return texture_.id(); }
  Extent extent() const { return extent_; }
  unsigned internalFormat() const { return internalFormat_; }

 private:
  std::optional<SceneDepthSource> source_;
  gl::Texture texture_;
  gl::Framebuffer read_, draw_;
  Extent extent_;
  unsigned internalFormat_ = 0;
};

}  // namespace rgraph
