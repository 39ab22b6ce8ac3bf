// gbuffer_view: shows one G-buffer target (the PBR chapter's debug views):
// position with a log mapping, normal as |n| or n * 0.5 + 0.5, albedo,
// specular, metallic, roughness, linear depth.
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

const std::vector<std::string> kViews = {"position", "normal_abs", "normal", "albedo",
                                         "specular", "metallic",   "roughness", "depth"};

class GBufferViewPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (!ctx.gpuScene()) throw RuntimeError("gbuffer_view pass '" + ctx.passName() + "' needs a scene");
    lighting::requireGBuffer(ctx, "gbuffer_view");
    program_ = ctx.shaders().program("fullscreen.vert", "gbuffer_view.frag", lighting::gbufferDefines(ctx.params()));
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
    const std::string view = ctx.params().getString("view", "albedo");
    int mode = 3;
    for (size_t i = 0; i < kViews.size(); ++i)
      if (kViews[i] == view) mode = static_cast<int>(i);
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_mode"), mode);
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    ctx.gpuScene()->bindFrame();
    lighting::bindGBuffer(ctx);
    triangle_->draw();
  }

 private:
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

PassTypeDesc makeGBufferViewPass() {
  using namespace rgraph::decl;
  PassTypeDesc d;
  d.name = "gbuffer_view";
  d.description = "Debug view of one G-buffer target (position, normal, albedo, specular, metallic, roughness, depth)";
  d.slots = lighting::gbufferSlots();
  d.slots.push_back(slot("color", Access::color_attachment, true, SlotDecl::Load::never, "the view"));
  d.params = {param("view", ParamType::enumeration, std::string("albedo"), "which target to show", kViews),
              lighting::layoutParam()};
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = lighting::adaptGBuffer;
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = "gbuffer_view.frag";
    s.defines = lighting::gbufferDefines(p);
    s.samplers = lighting::gbufferSamplers();
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"fullscreen.vert", "gbuffer_view.frag"};
  d.create = [] { return std::make_unique<GBufferViewPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeGBufferViewPass);
}  // namespace
