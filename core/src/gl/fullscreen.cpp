#include "rgraph/gl/fullscreen.h"

#include <GL/glcorearb.h>

namespace rgraph::gl {

FullscreenTriangle::FullscreenTriangle() : vao_(createVertexArray()) {}

void FullscreenTriangle::draw() const {
  glBindVertexArray(vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

void bindPassFramebuffer(PassContext& ctx) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, ctx.framebuffer());
  Extent e = ctx.framebufferExtent();
  glViewport(0, 0, static_cast<GLsizei>(e.width), static_cast<GLsizei>(e.height));
}

void bindSampler(uint32_t program, const char* name, uint32_t unit, uint32_t texture) {
  GLint loc = glGetUniformLocation(program, name);
  if (loc < 0) return;
  glProgramUniform1i(program, loc, static_cast<GLint>(unit));
  glBindTextureUnit(unit, texture);
}

}  // namespace rgraph::gl
