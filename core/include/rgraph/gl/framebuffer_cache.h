// The executor's framebuffers and texture views, made once per plan and
// shared by every pass: a framebuffer is found by the exact set of images it
// attaches (texture, mip level, layer or every layer, attachment point) and
// its draw buffers, a view by the texture and the level and layer range it
// shows. Passes never create either themselves (PassContext::framebuffer,
// PassContext::texture(slot, sub)).
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/gl/objects.h"

namespace rgraph::gl {

// One image of a framebuffer.
struct FramebufferAttachment {
  static constexpr uint32_t kAllLayers = Subresource::kAll;
  unsigned point = 0;      // GL_COLOR_ATTACHMENT0 + i, GL_DEPTH_ATTACHMENT or GL_DEPTH_STENCIL_ATTACHMENT
  uint32_t texture = 0;    // GL name
  uint32_t level = 0;      // mip level
  // Array layer (cube face: 6 * cube + face) of an array or cube texture,
  // attached alone; kAllLayers: the whole texture (a layered attachment when
  // it has layers: the shader picks one with gl_Layer).
  uint32_t layer = kAllLayers;
  // Described in messages only, never part of the key.
  std::string slot;
  Format format = Format::rgba8;
  Extent extent;           // of `level`
  uint32_t samples = 1;
};

// "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT" and the other statuses by name;
// one GL does not define: "unknown status 0x8cd5" (hexadecimal).
std::string framebufferStatusName(unsigned status);
// The one message an incomplete framebuffer gives: its status by name and
// every attachment, e.g. "framebuffer incomplete: GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT
// (attachments: color=rgba8 64x64 level 1, depth=depth24 32x32 layer 3)".
std::string framebufferStatusMessage(unsigned status, std::span<const FramebufferAttachment> attachments);

class FramebufferCache {
 public:
  // The framebuffer attaching exactly `attachments` with these draw buffers
  // (GL_NONE entries allowed; empty: GL_NONE), the read buffer the first
  // colour attachment (else GL_NONE). Made and checked for completeness the
  // first time this set is asked for; the same name every later time until
  // clear(). Throws RuntimeError "WHO: framebuffer incomplete: ..." when it
  // is not complete (nothing is cached then).
  uint32_t get(std::span<const FramebufferAttachment> attachments, std::span<const unsigned> drawBuffers,
               std::string_view who);
  // A view (glTextureView) of levels [sub.mipBegin, +mipCount) and layers
  // [sub.layerBegin, +layerCount) of `texture` (counts resolved, never kAll),
  // as a texture of `target` (GL_TEXTURE_2D for one layer of an array or a
  // cube, ...), the texture's internal format. Made the first time, then the
  // same name until clear(). `texture` must have immutable storage.
  uint32_t view(uint32_t texture, unsigned target, unsigned internalFormat, const Subresource& sub);
  size_t framebuffers() const { return fbos_.size(); }
  size_t views() const { return views_.size(); }
  // Deletes everything (the textures they show are about to go or change).
  void clear();

 private:
  std::map<std::vector<uint32_t>, Framebuffer> fbos_;
  std::map<std::vector<uint32_t>, Texture> views_;
};

}  // namespace rgraph::gl
