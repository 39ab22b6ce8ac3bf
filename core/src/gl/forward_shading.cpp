#include "rgraph/gl/forward_shading.h"

#include <GL/glcorearb.h>

#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/lighting_options.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/scene.h"

namespace rgraph::forward {

uint32_t program(PassContext& ctx) {
  std::vector<std::string> defines = lighting::defines(ctx.params());
  if (ctx.scene() && ctx.scene()->hasNormalMaps()) defines.push_back("HAS_NORMAL_MAPS");
  return ctx.shaders().program("scene.vert", "forward_lit.frag", defines);
}

void drawSurfaces(PassContext& ctx, uint32_t prog, bool blended) {
  GpuScene& scene = *ctx.gpuScene();
  const GpuScene::Filter filter = blended ? GpuScene::Filter::blend : GpuScene::Filter::opaque;
  if (scene.primitiveCount(filter) == 0) return;
  scene.bindFrame();
  scene.bindPointLights(lighting::threshold(ctx.params()));
  glUseProgram(prog);
  glProgramUniform1i(prog, glGetUniformLocation(prog, "u_pointLightCount"), static_cast<int>(scene.pointLightCount()));
  glProgramUniform1i(prog, glGetUniformLocation(prog, "u_blendPass"), blended ? 1 : 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (blended) {
    // Blended surfaces are tested against the opaque depth but do not write
    // it, so those behind them stay visible through them.
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  } else {
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  GpuScene::DrawOptions options;
  options.filter = filter;
  options.backToFront = blended;
  scene.drawPrimitives(prog, options);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace rgraph::forward
