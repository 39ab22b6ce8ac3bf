// Executor::setStateChecks: a pass's changedState() against the GL state it
// actually leaves behind (the executor trusts it and skips the resets).
#include <GL/glcorearb.h>

#include <string>

#include "executor_internal.h"
#include "rgraph/error.h"

namespace rgraph {

void Executor::Impl::checkState(const exec_detail::PassRun& run) const {
  const uint32_t declared = run.instance->changedState() | (run.readOnlyDepth ? kGlStateDepth : 0u);
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
      {kGlStateDepth, "depth writes are off", integer(GL_DEPTH_WRITEMASK) == GL_TRUE},
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
}

}  // namespace rgraph
