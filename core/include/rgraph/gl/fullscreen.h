// Helpers for passes that draw a fullscreen triangle.
#pragma once

#include <cstdint>
#include <string>

#include "rgraph/gl/objects.h"
#include "rgraph/pass.h"

namespace rgraph::gl {

// An empty vertex array (core profile needs one bound) and a 3-vertex draw.
// Use with shaders/fullscreen.vert, which derives positions from gl_VertexID.
class FullscreenTriangle {
 public:
  FullscreenTriangle();  // needs a current context
  void draw() const;     // binds its VAO and draws 3 vertices
 private:
  VertexArray vao_;
};

// Binds ctx.framebuffer() as draw framebuffer and sets the viewport to its extent.
void bindPassFramebuffer(PassContext& ctx);

// Sets `uniform sampler2D NAME` of `program` to texture unit `unit` and binds
// `texture` there (0 unbinds). No-op when the uniform does not exist.
void bindSampler(uint32_t program, const char* name, uint32_t unit, uint32_t texture);

}  // namespace rgraph::gl
