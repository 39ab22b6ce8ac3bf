#include "rgraph/passes/forward_shading.h"

#include <GL/glcorearb.h>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/passes/cluster_lists.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/passes/velocity.h"
#include "rgraph/scene.h"

namespace rgraph::forward {

std::vector<ShaderProgramSpec> programs(const ParamSet& params, bool blendsSourceAlpha) {
  std::vector<std::string> defines = lighting::defines(params);
  velocity::addDefine(params, defines);  // forward_lit's "velocity" (absent elsewhere: off)
  ShaderProgramSpec s = programSpec("scene.vert", "forward_lit.frag", std::move(defines));
  s.ownSamplers = lighting::materialSamplers();
  s.blendsSourceAlpha = blendsSourceAlpha;
  shadows::addToProgram(s, params);
  ibl::addToProgram(s, params);
  return lighting::normalMapVariants(s);
}

SurfaceDrawer::SurfaceDrawer(uint32_t program)
    : program_(program), pointLightCount_(program, "u_pointLightCount"), blendPass_(program, "u_blendPass"),
      clustered_(program, "u_clustered") {}

void SurfaceDrawer::draw(PassContext& ctx, bool blended) const {
  GpuScene& scene = *ctx.gpuScene();
  const GpuScene::Filter filter = blended ? GpuScene::Filter::blend : GpuScene::Filter::opaque;
  if (scene.primitiveCount(filter) == 0) return;
  lighting::bindPointLights(scene, lighting::threshold(ctx.params()));
  shadows::bindInfo(ctx, program_);
  ibl::setUniforms(ctx, program_);
  const uint32_t prog = program_;
  gl::useProgram(ctx, prog);
  pointLightCount_.set(static_cast<int>(scene.pointLightCount()));
  blendPass_.set(blended);
  const bool clustered = ctx.bound(clusters::kSlot);
  clustered_.set(clustered);
  if (clustered) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, clusters::kBinding, ctx.buffer(clusters::kSlot));
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (blended) {
    // Blended surfaces are tested against the opaque depth but do not write
    // it, so those behind them stay visible through them.
    glDepthMask(GL_FALSE);
    // Motion vectors (draw buffer 1 when bound) stay those of the opaque
    // surface behind: a blend of two motions is neither's.
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
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
  glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
}

}  // namespace rgraph::forward
