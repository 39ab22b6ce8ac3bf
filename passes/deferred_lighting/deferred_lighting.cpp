// deferred_lighting: a fullscreen pass that shades every pixel of the
// G-buffer once: ambient, the directional light, and the point lights (all of
// them, or none when a light_volumes pass draws those).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/lighting_options.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class DeferredLightingPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (!ctx.gpuScene()) throw RuntimeError("deferred_lighting pass '" + ctx.passName() + "' needs a scene");
    lighting::requireGBuffer(ctx, "deferred_lighting");
    std::vector<std::string> defines = lighting::defines(ctx.params());
    for (auto& def : lighting::gbufferDefines(ctx.params())) defines.push_back(std::move(def));
    if (ctx.params().getBool("radius_test", false)) defines.push_back("LIGHT_RADIUS_BRANCH");
    program_ = ctx.shaders().program("fullscreen.vert", "deferred_lighting.frag", defines);
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    gl::bindPassFramebuffer(ctx);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    const bool points = ctx.params().getBool("point_lights", true);
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_pointLightCount"),
                       points ? static_cast<int>(scene.pointLightCount()) : 0);
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_ambientAndSun"), 1);
    scene.bindFrame();
    scene.bindPointLights(lighting::threshold(ctx.params()));
    lighting::bindGBuffer(ctx);
    // Optional ambient occlusion (e.g. the ssao plugin's output) scales the ambient term.
    const bool ao = ctx.bound("ao");
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_hasAo"), ao ? 1 : 0);
    glBindTextureUnit(5, ao ? ctx.texture("ao") : 0);
    triangle_->draw();
  }

 private:
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

PassTypeDesc makeDeferredLightingPass() {
  using namespace rgraph::decl;
  PassTypeDesc d;
  d.name = "deferred_lighting";
  d.description = "Fullscreen deferred lighting: ambient, directional and point lights from the G-buffer";
  d.slots = lighting::gbufferSlots();
  d.slots.push_back(slot("color", Access::color_attachment, true, SlotDecl::Load::optional,
                         "HDR lighting target; background pixels keep its clear value",
                         {Format::rgba16f, Format::rgba32f, Format::r11g11b10f}));
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
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = "deferred_lighting.frag";
    s.defines = lighting::defines(p);
    for (auto& def : lighting::gbufferDefines(p)) s.defines.push_back(std::move(def));
    if (p.getBool("radius_test", false)) s.defines.push_back("LIGHT_RADIUS_BRANCH");
    s.samplers = lighting::gbufferSamplers();
    s.samplers.push_back({"ao", "u_ao", 5, /*optional=*/true});  // u_hasAo says whether it is bound
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"fullscreen.vert", "deferred_lighting.frag"};
  d.create = [] { return std::make_unique<DeferredLightingPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeDeferredLightingPass);
}  // namespace
