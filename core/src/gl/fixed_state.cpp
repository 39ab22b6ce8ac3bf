#include "fixed_state.h"

#include <GL/glcorearb.h>

namespace rgraph::gl {

namespace {
void enable(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }
GLboolean b(bool v) { return v ? GL_TRUE : GL_FALSE; }
}  // namespace

void applyFixedState(const FixedState& s) {
  enable(GL_BLEND, s.blend);
  glBlendFuncSeparate(s.blendSrcRgb, s.blendDstRgb, s.blendSrcAlpha, s.blendDstAlpha);
  glBlendEquationSeparate(s.blendEquationRgb, s.blendEquationAlpha);
  glBlendColor(s.blendColor[0], s.blendColor[1], s.blendColor[2], s.blendColor[3]);
  enable(GL_DEPTH_TEST, s.depthTest);
  glDepthFunc(s.depthFunc);
  glDepthMask(b(s.depthMask));
  enable(GL_STENCIL_TEST, s.stencilTest);
  glStencilFunc(s.stencilFunc, s.stencilRef, s.stencilValueMask);
  glStencilOp(s.stencilFail, s.stencilDepthFail, s.stencilPass);
  glStencilMask(s.stencilWriteMask);
  enable(GL_CULL_FACE, s.cullFace);
  glCullFace(s.cullMode);
  glFrontFace(s.frontFace);
  enable(GL_SCISSOR_TEST, s.scissorTest);
  glScissor(s.scissor[0], s.scissor[1], s.scissor[2], s.scissor[3]);
  glViewport(s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]);
  glColorMask(b(s.colorMask[0]), b(s.colorMask[1]), b(s.colorMask[2]), b(s.colorMask[3]));
  enable(GL_FRAMEBUFFER_SRGB, s.framebufferSrgb);
}

const FixedState& hostileFixedState() {
  static const FixedState hostile = [] {
    FixedState s;
    s.blend = true;
    s.blendSrcRgb = s.blendDstRgb = s.blendSrcAlpha = s.blendDstAlpha = GL_ONE;
    s.blendEquationRgb = s.blendEquationAlpha = GL_FUNC_REVERSE_SUBTRACT;
    s.blendColor = {0.5f, 0.25f, 0.125f, 0.0f};
    s.depthTest = true;
    s.depthFunc = GL_NEVER;
    s.depthMask = false;
    s.stencilTest = true;
    s.stencilFunc = GL_NEVER;
    s.stencilRef = 0x5A;
    s.stencilValueMask = 0x0F;
    s.stencilFail = s.stencilDepthFail = s.stencilPass = GL_INVERT;
    s.stencilWriteMask = 0;
    s.cullFace = true;
    s.cullMode = GL_FRONT_AND_BACK;
    s.frontFace = GL_CW;
    s.scissorTest = true;
    s.scissor = {1, 1, 1, 1};
    s.viewport = {3, 5, 7, 9};
    s.colorMask = {false, true, false, true};
    s.framebufferSrgb = false;
    return s;
  }();
  return hostile;
}

}  // namespace rgraph::gl
