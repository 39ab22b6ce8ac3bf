// deferred_lighting: a fullscreen pass that shades every pixel of the
// G-buffer once: ambient, the directional light, and the point lights (all of
// them, or none when a light_volumes pass draws those).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class DeferredLightingPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const bool points = ctx.params().getBool("point_lights");
    pointLightCount_.set(points ? static_cast<int>(scene.pointLightCount()) : 0);
    ambientAndSun_.set(1);
    // Optional ambient occlusion (e.g. the ssao plugin's output) scales the ambient term.
    hasAo_.set(ctx.bound("ao"));
    ibl::setUniforms(ctx, program());
    lighting::bindPointLights(scene, lighting::threshold(ctx.params()));
    shadows::bindInfo(ctx, program());
  }
  uint32_t changedState() const override { return 0; }  // uniforms and the scene's buffers only
  ProgramUniform pointLightCount_{this, "u_pointLightCount"}, ambientAndSun_{this, "u_ambientAndSun"};
  ProgramUniform hasAo_{this, "u_hasAo"};
};

PassTypeDesc makeDeferredLightingPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::gbufferReader(
      "deferred_lighting", "Fullscreen deferred lighting: ambient, directional and point lights from the G-buffer");
  d.slots.push_back(slot("color", Access::color_attachment, true, SlotDecl::Load::optional,
                         "HDR lighting target; background pixels keep its clear value",
                         hdrFormats()));
  d.slots.push_back(slot("ao", Access::sampled, false, SlotDecl::Load::never,
                         "ambient occlusion (r channel, any size) that scales the ambient term, e.g. from ssao",
                         {Format::r8, Format::r16f, Format::r32f, Format::rg8, Format::rg16f}));
  d.params = lighting::params();
  d.params.push_back(lighting::layoutParam());
  d.params.push_back(param("point_lights", ParamType::boolean, true,
                           "shade the point lights here (false when a light_volumes pass draws them)"));
  d.params.push_back(param("radius_test", ParamType::boolean, false,
                           "skip a light's maths beyond its radius with a branch (LearnOpenGL's loop)"));
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = lighting::adaptPointLightShading;
  shadows::declareReader(d);
  ibl::declareReader(d);
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s = gl::fullscreenProgram("deferred_lighting.frag", lighting::gbufferSamplers(),
                                                lighting::shadingDefines(p));
    if (p.getBool("radius_test")) s.defines.push_back("LIGHT_RADIUS_BRANCH");
    s.samplers.push_back({"ao", "u_ao", 5, /*optional=*/true});  // u_hasAo says whether it is bound
    shadows::addToProgram(s, p);
    ibl::addToProgram(s, p);
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.create = [] { return std::make_unique<DeferredLightingPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeDeferredLightingPass);
}  // namespace
