#include "rgraph/gl/fullscreen.h"

#include <GL/glcorearb.h>

namespace rgraph::gl {

FullscreenTriangle::FullscreenTriangle() : vao_(createVertexArray()), id_(vao_.id()) {}

void FullscreenTriangle::draw() const {
  glBindVertexArray(id_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void FullscreenTriangle::draw(PassContext& ctx) const {
  bindVertexArray(ctx, id_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void bindPassFramebuffer(PassContext& ctx) {
  GlBindings none;
  GlBindings& b = ctx.bindings() ? *ctx.bindings() : none;
  const uint32_t fbo = ctx.framebuffer();
  if (b.drawFramebuffer != fbo) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
  b.drawFramebuffer = fbo;
  const Extent e = ctx.framebufferExtent();
  if (b.viewportWidth != e.width || b.viewportHeight != e.height)
    glViewport(0, 0, static_cast<GLsizei>(e.width), static_cast<GLsizei>(e.height));
  b.viewportWidth = e.width;
  b.viewportHeight = e.height;
}

PassFramebuffer bindPassFramebuffer(PassContext& ctx, std::initializer_list<AttachmentRef> attachments,
                                    FramebufferTarget target) {
  const PassFramebuffer fb = ctx.framebuffer(attachments);
  if (target == FramebufferTarget::read) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id);
    return fb;
  }
  GlBindings none;
  GlBindings& b = ctx.bindings() ? *ctx.bindings() : none;
  if (b.drawFramebuffer != fb.id) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id);
  b.drawFramebuffer = fb.id;
  if (b.viewportWidth != fb.extent.width || b.viewportHeight != fb.extent.height)
    glViewport(0, 0, static_cast<GLsizei>(fb.extent.width), static_cast<GLsizei>(fb.extent.height));
  b.viewportWidth = fb.extent.width;
  b.viewportHeight = fb.extent.height;
  return fb;
}

void useProgram(PassContext& ctx, uint32_t program) {
  GlBindings* b = ctx.bindings();
  if (b && b->program == program) return;
  glUseProgram(program);
  if (b) b->program = program;
}

void bindVertexArray(PassContext& ctx, uint32_t vertexArray) {
  GlBindings* b = ctx.bindings();
  if (b && b->vertexArray == vertexArray) return;
  glBindVertexArray(vertexArray);
  if (b) b->vertexArray = vertexArray;
}

ShaderProgramSpec fullscreenProgram(std::string frag, std::vector<SamplerSlot> samplers,
                                    std::vector<std::string> defines) {
  return programSpec("fullscreen.vert", std::move(frag), std::move(defines), std::move(samplers));
}

std::function<std::vector<ShaderProgramSpec>(const ParamSet&)> fullscreenPrograms(std::string frag,
                                                                                  std::vector<SamplerSlot> samplers) {
  return [spec = fullscreenProgram(std::move(frag), std::move(samplers))](const ParamSet&) {
    return std::vector<ShaderProgramSpec>{spec};
  };
}

void FullscreenPass::setup(PassContext& ctx) {
  program_ = ctx.program(programIndex_);
  for (ProgramUniform* u : uniforms_) static_cast<Uniform&>(*u) = Uniform(program_, u->name_);
  if (ctx.emptyVertexArray())
    triangle_ = std::make_unique<FullscreenTriangle>(ctx.emptyVertexArray());
  else if (!triangle_)
    triangle_ = std::make_unique<FullscreenTriangle>();
  prepare(ctx);
}

void FullscreenPass::execute(PassContext& ctx) {
  bindPassFramebuffer(ctx);
  useProgram(ctx, program_);
  update(ctx);
  triangle_->draw(ctx);
}

}  // namespace rgraph::gl
