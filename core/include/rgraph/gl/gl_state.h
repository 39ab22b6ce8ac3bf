// The caller's GL state around an rgraph frame (rgraph/renderer.h, "GL state
// contract"): captured before the frame, put back after it.
//
//   {
//     rgraph::gl::GlStateGuard guard;   // captures
//     rgraph::gl::applyRendererDefaults();
//     executor.renderFrame();           // changes whatever it needs
//   }                                   // restores
//
// What is saved (the contract's list, plus what rgraph's passes change beyond
// it, plus what applyRendererDefaults() changes, plus a few cheap bindings):
//   - draw and read framebuffers, current program, vertex array; buffers bound
//     to GL_ARRAY_BUFFER, GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER,
//     GL_PIXEL_PACK_BUFFER and GL_PIXEL_UNPACK_BUFFER;
//   - viewport and scissor box (index 0; glViewport/glScissor set every index);
//   - enables: depth test, stencil test, cull face, scissor test, framebuffer
//     sRGB, polygon offset fill, multisample, depth clamp, rasterizer discard,
//     colour logic op, primitive restart (both), sample alpha to coverage,
//     sample coverage, sample mask; blend per draw buffer;
//   - per draw buffer 0-7: blend functions and equations (RGB and alpha
//     separately) and colour mask; the blend colour;
//   - depth function and mask; stencil functions, value masks, write masks and
//     operations, front and back;
//   - cull face mode, front face, polygon mode, clip control;
//   - the active texture unit; on units 0-15, the texture bound to every
//     target (1D, 2D, 3D, arrays, cube maps, rectangle, buffer, multisample:
//     rgraph's glBindTextureUnit(unit, 0) unbinds them all) and the sampler;
//   - uniform and shader storage buffer bindings 0-7 with their ranges (a
//     range binding comes back as the same range, a whole-buffer binding as a
//     whole-buffer binding);
//   - image units 0-7: texture, level, layered, layer, access, format;
//   - pixel pack and unpack alignment, row length, image height and skips.
// Not saved: object contents (a texture's parameters, a framebuffer's
// attachments and draw buffers, a VAO's attributes), draw buffers 8 and up,
// viewports and scissor boxes past index 0, values only enables use
// (polygon offset factors, logic op, sample coverage value and mask,
// primitive restart index), clear values, depth range.
//
// Restoring binds the saved names again: a caller object deleted in between
// cannot come back (GL reports an error). Needs a current GL 4.5 context.
// Cost on llvmpipe (medians): about 4 us to capture, 2-3 us to restore
// (GlStateTest.CaptureAndRestoreCost prints it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace rgraph::gl {

class SavedState {
 public:
  // Reads the state (leaves it as it was; needs a current context).
  static SavedState capture();
  // Sets the state back to what capture() read.
  void restore() const;

  // How many integer values one capture holds (checked against the tables
  // in gl_state.cpp at compile time).
  static constexpr size_t kValueCount = 443;

 private:
  SavedState() = default;
  std::array<int64_t, kValueCount> values_{};
  std::array<float, 4> blendColor_{};
};

// Sets what rgraph's passes take for granted and a caller may have changed
// to GL's initial values: polygon mode fill, multisample on; polygon offset
// fill, rasterizer discard, colour logic op, primitive restart, sample alpha
// to coverage, sample coverage and sample mask off; clip control lower-left,
// -1..1; pixel pack and unpack store at their defaults and no pixel pack or
// unpack buffer (scene uploads and read-backs go through them); no sampler
// object on units 0-15 (a pass sampling through a unit it was given no
// sampler for filters with the texture's own parameters). Only state
// SavedState saves: call it inside a GlStateGuard.
void applyRendererDefaults();

// Captures at construction, restores at destruction.
class GlStateGuard {
 public:
  GlStateGuard() : saved_(SavedState::capture()) {}
  ~GlStateGuard() { saved_.restore(); }
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

  const SavedState& saved() const { return saved_; }

 private:
  SavedState saved_;
};

}  // namespace rgraph::gl
