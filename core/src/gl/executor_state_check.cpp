// Executor::setStateChecks: a pass's changedState() against the GL state it
// actually leaves behind (the executor trusts it and skips the resets).
#include <GL/glcorearb.h>

#include <string>

#include "executor_internal.h"
#include "rgraph/error.h"

namespace rgraph {

void Executor::Impl::checkState(const exec_detail::PassRun& run) const {
  const uint32_t declared = run.instance->changedState();
  auto integer = [](GLenum pname) {
    GLint v = 0;
    glGetIntegerv(pname, &v);
    return v;
  };
  GLboolean mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  glGetBooleanv(GL_COLOR_WRITEMASK, mask);
  struct Item {
    uint32_t group;
    const char* what;
    bool asReset;
  };
  const Item items[] = {
      {kGlStateBlend, "GL_BLEND is on", !glIsEnabled(GL_BLEND)},
      {kGlStateDepth, "GL_DEPTH_TEST is on", !glIsEnabled(GL_DEPTH_TEST)},
      {kGlStateDepth, "the depth function is not GL_LESS", integer(GL_DEPTH_FUNC) == GL_LESS},
      // A read-only depth pass runs with writes off (the executor turned them off and puts them back).
      {kGlStateDepth, "depth writes are off", run.readOnlyDepth || integer(GL_DEPTH_WRITEMASK) == GL_TRUE},
      {kGlStateStencil, "GL_STENCIL_TEST is on", !glIsEnabled(GL_STENCIL_TEST)},
      {kGlStateStencil, "the stencil write mask is not 0xFF", (integer(GL_STENCIL_WRITEMASK) & 0xFF) == 0xFF},
      {kGlStateCull, "GL_CULL_FACE is on", !glIsEnabled(GL_CULL_FACE)},
      {kGlStateScissor, "GL_SCISSOR_TEST is on", !glIsEnabled(GL_SCISSOR_TEST)},
      {kGlStateColorMask, "a colour channel is masked", mask[0] && mask[1] && mask[2] && mask[3]},
      {kGlStateSrgb, "GL_FRAMEBUFFER_SRGB is off", glIsEnabled(GL_FRAMEBUFFER_SRGB) == GL_TRUE},
  };
  for (const Item& i : items)
    if (!(declared & i.group) && !i.asReset)
      throw RuntimeError("pass '" + run.name + "' of type '" + run.typeName + "' left state changed: " + i.what +
                         ", but its changedState() says it leaves that group as it found it");
  if (!(declared & kGlStateBindings)) checkBindings(run);
  checkSamplers(run);
}

// Sampler 0 on every unit when a pass starts is a promise to every pass
// (pass_programs.h: a pass binding a texture itself needs no sampler call),
// kept by each pass putting back 0 where it bound a sampler object: whatever
// its changedState() says, a pass that leaves one changes how the next pass
// to sample that unit filters.
void Executor::Impl::checkSamplers(const exec_detail::PassRun& run) const {
  GLint active = GL_TEXTURE0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  GLuint unit = 0;
  GLint sampler = 0;
  for (; unit < 16 && sampler == 0; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_SAMPLER_BINDING, &sampler);
  }
  glActiveTexture(static_cast<GLenum>(active));
  if (sampler != 0)
    throw RuntimeError("pass '" + run.name + "' of type '" + run.typeName + "' left sampler object " +
                       std::to_string(sampler) + " bound on texture unit " + std::to_string(unit - 1) +
                       ": every pass starts with sampler 0 on every unit, so a pass that binds a sampler puts 0 back");
}

// The executor's record (GlBindings) against what is bound: a pass that binds
// with raw GL calls and leaves kGlStateBindings out of changedState() would
// make the next pass skip a bind it needs.
void Executor::Impl::checkBindings(const exec_detail::PassRun& run) const {
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  auto integer = [](GLenum pname) {
    GLint v = 0;
    glGetIntegerv(pname, &v);
    return static_cast<uint32_t>(v);
  };
  auto indexed = [](GLenum pname) {
    GLint v = 0;
    glGetIntegeri_v(pname, 0, &v);
    return static_cast<uint32_t>(v);
  };
  const auto known = [](uint32_t scene) { return scene ? scene : GlBindings::kUnknown; };
  struct Item {
    const char* what;
    uint32_t recorded, actual;
  };
  const Item items[] = {
      {"draw framebuffer", bound.drawFramebuffer, integer(GL_DRAW_FRAMEBUFFER_BINDING)},
      {"viewport width", bound.viewportWidth, static_cast<uint32_t>(viewport[2])},
      {"viewport height", bound.viewportHeight, static_cast<uint32_t>(viewport[3])},
      {"program", bound.program, integer(GL_CURRENT_PROGRAM)},
      {"vertex array", bound.vertexArray, integer(GL_VERTEX_ARRAY_BINDING)},
      {"uniform buffer at 0 (the Frame block)", gpuScene ? known(gpuScene->recordedFrameBinding()) : GlBindings::kUnknown,
       indexed(GL_UNIFORM_BUFFER_BINDING)},
      {"storage buffer at 0 (the scene's lights)",
       gpuScene ? known(gpuScene->recordedLightBinding()) : GlBindings::kUnknown,
       indexed(GL_SHADER_STORAGE_BUFFER_BINDING)},
  };
  for (const Item& i : items)
    if (i.recorded != GlBindings::kUnknown && i.recorded != i.actual)
      throw RuntimeError("pass '" + run.name + "' of type '" + run.typeName + "' bound another " + i.what + " (" +
                         std::to_string(i.actual) + ", the executor's record says " + std::to_string(i.recorded) +
                         ") without PassContext::bindings(), but its changedState() leaves out kGlStateBindings");
}

}  // namespace rgraph
