#include "rgraph/passes/ibl.h"

#include <GL/glcorearb.h>

#include <string>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/scene.h"

namespace rgraph::ibl {

std::vector<Format> cubeFormats() { return {Format::rgba16f, Format::rgba32f}; }

void drawFaces(PassContext& ctx, uint32_t program, std::string_view slot, uint32_t levels,
               const std::function<void(uint32_t)>& perLevel) {
  gl::useProgram(ctx, program);
  gl::bindVertexArray(ctx, ctx.emptyVertexArray());
  const GLint face = glGetUniformLocation(program, "u_face");
  for (uint32_t level = 0; level < levels; ++level) {
    if (perLevel) perLevel(level);
    for (uint32_t f = 0; f < 6; ++f) {
      gl::bindPassFramebuffer(ctx, {AttachmentRef{slot, level, f}});
      glProgramUniform1i(program, face, static_cast<GLint>(f));
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
}

uint32_t levels(PassContext& ctx, std::string_view slot) {
  GLint n = 1;
  glGetTextureParameteriv(ctx.texture(slot), GL_TEXTURE_IMMUTABLE_LEVELS, &n);
  return static_cast<uint32_t>(n > 0 ? n : 1);
}

void declareReader(PassTypeDesc& d) {
  using namespace rgraph::decl;
  d.slots.push_back(slot("irradiance", Access::sampled, false, SlotDecl::Load::never,
                         "IBL: the environment's irradiance / pi (a cube, from irradiance_cube)", cubeFormats()));
  d.slots.push_back(slot("specular", Access::sampled, false, SlotDecl::Load::never,
                         "IBL: the pre-filtered environment, roughness along its mips (a cube, from specular_cube)",
                         cubeFormats()));
  d.slots.push_back(slot("brdf_lut", Access::sampled, false, SlotDecl::Load::never,
                         "IBL: the split-sum's scale and bias of F0 (from brdf_lut)", {Format::rg16f}));
  d.params.push_back(param("ibl", ParamType::boolean, false,
                           "image-based lighting: ambient from the irradiance, specular and brdf_lut inputs (turned "
                           "off by scene adaptation when the scene has no environment)"));
  PassRule rule;
  rule.text = "with ibl, bind irradiance, specular and brdf_lut";
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    if (!ctx.params().getBool("ibl")) return;
    for (const char* s : {"irradiance", "specular", "brdf_lut"})
      if (!ctx.bound(s)) checks.slotError(s, std::string("input '") + s + "' is required by \"ibl\": true but not bound");
  };
  d.rules.push_back(std::move(rule));
  d.adapt = [own = std::move(d.adapt)](const SceneFeatures& f, PassAdaptation& a) {
    if (own) own(f, a);
    adapt(f, a);
  };
}

void setUniforms(PassContext& ctx, uint32_t program) {
  if (!ctx.params().getBool("ibl")) return;
  glProgramUniform1i(program, glGetUniformLocation(program, "u_hasEnvironment"),
                     ctx.scene() && ctx.scene()->environment ? 1 : 0);
}

void addToProgram(ShaderProgramSpec& s, const ParamSet& p) {
  if (!p.getBool("ibl")) return;
  s.defines.push_back("HAS_ENVIRONMENT");
  s.samplers.push_back({"irradiance", "u_iblIrradiance", 13});
  s.samplers.push_back({"specular", "u_iblSpecular", 14});
  s.samplers.push_back({"brdf_lut", "u_iblBrdfLut", 15});
}

void adapt(const SceneFeatures& f, PassAdaptation& a) {
  if (f.environment) return;
  a.unbindSlots.insert(a.unbindSlots.end(), {"irradiance", "specular", "brdf_lut"});
  if (!a.params.getBool("ibl")) return;
  a.params.set("ibl", false);
  a.notes.push_back("no environment: the constant ambient, no image-based lighting");
}

}  // namespace rgraph::ibl
