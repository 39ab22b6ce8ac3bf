// The GL state contract seen from the caller's side (rgraph/renderer.h): a
// program's own drawing, with its state set once and used after something
// else (an rgraph frame) ran in between. Any state the frame leaves changed
// that the drawing relies on changes its pixels.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph::testsupport {

// The caller's objects: a framebuffer (SRGB8_ALPHA8 colour + DEPTH24_STENCIL8),
// a program, a vertex array with its vertex buffer, a texture with a sampler
// object of other filtering on unit 0, a uniform block bound as a range at
// binding 0 (the buffer's start holds a wrong tint), a storage block at
// binding 0, and a texture it re-uploads every draw relying on its unpack
// alignment of 1. Its state: viewport and scissor box inside the target,
// scissor test, blend (separate functions, the blend colour), depth test
// GL_GREATER, stencil test, back faces culled with clockwise front faces,
// framebuffer sRGB on, blue not written. Needs a current GL 4.5 context.
class CallerDrawing {
 public:
  explicit CallerDrawing(Extent size = {64, 64});
  ~CallerDrawing();
  CallerDrawing(const CallerDrawing&) = delete;
  CallerDrawing& operator=(const CallerDrawing&) = delete;

  // Sets the caller's state, clears its framebuffer, calls `frame` (may be
  // empty), re-uploads the caller's texture and draws its triangles with
  // whatever state is current then, and reads its framebuffer back (RGBA8
  // stored bytes, rows bottom-up). Compare with drawAround({}) exactly.
  std::vector<uint8_t> drawAround(const std::function<void()>& frame);

  Extent size() const { return size_; }
  uint32_t framebuffer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Extent size_;
};

// Pixels where two RGBA8 images of `size` differ; `first` (if given) gets the
// first one's position and both values.
size_t differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, Extent size,
                       std::string* first = nullptr);

}  // namespace rgraph::testsupport
