// tonemap: HDR lighting target -> the 8-bit output (exposure, Reinhard or
// ACES, sRGB transfer).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class TonemapPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (ctx.extent("hdr") != ctx.framebufferExtent())
      throw RuntimeError("tonemap pass '" + ctx.passName() + "': 'hdr' and 'output' must have the same size");
    program_ = ctx.shaders().program("fullscreen.vert", "tonemap.frag");
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
    const ParamSet& p = ctx.params();
    const std::string op = p.getString("operator", "aces");
    glProgramUniform1f(program_, glGetUniformLocation(program_, "u_exposure"),
                       static_cast<float>(p.getNumber("exposure", 1.0)));
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_operator"),
                       op == "reinhard" ? 0 : op == "aces" ? 1 : 2);
    // An sRGB target encodes on write; a linear rgba8 target gets the curve here.
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_encodeSrgb"),
                       gl::isSrgb(ctx.format("output")) ? 0 : 1);
    glProgramUniform1f(program_, glGetUniformLocation(program_, "u_gamma"), static_cast<float>(p.getNumber("gamma", 0.0)));
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    if (gl::isSrgb(ctx.format("output"))) glEnable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(program_);
    glBindTextureUnit(0, ctx.texture("hdr"));
    triangle_->draw();
    glDisable(GL_FRAMEBUFFER_SRGB);
  }

 private:
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

PassTypeDesc makeTonemapPass() {
  using namespace rgraph::decl;
  PassTypeDesc d;
  d.name = "tonemap";
  d.description = "HDR to the display: exposure, Reinhard or ACES, sRGB transfer";
  d.slots = {
      slot("hdr", Access::sampled, true, SlotDecl::Load::never, "HDR input (rgba16f, rgba32f, r11g11b10f)",
           {Format::rgba16f, Format::rgba32f, Format::r11g11b10f}),
      slot("output", Access::color_attachment, true, SlotDecl::Load::never, "display image (rgba8 or srgb8_alpha8)",
           {Format::rgba8, Format::srgb8_alpha8}),
  };
  d.params = {
      param("operator", ParamType::enumeration, std::string("aces"), "tone curve: reinhard, aces, or none (clamp)",
            {"reinhard", "aces", "none"}),
      ranged("exposure", ParamType::number, 1.0, 0.0, 1000.0, "multiplies the HDR colour before the curve"),
      ranged("gamma", ParamType::number, 0.0, 0.0, 5.0, "0: the exact sRGB curve; otherwise pow(c, 1/gamma)"),
  };
  d.programs = [](const ParamSet&) {
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = "tonemap.frag";
    s.samplers = {{"hdr", "u_hdr", 0}};  // bound on unit 0, read through layout(binding = 0)
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"fullscreen.vert", "tonemap.frag"};
  d.create = [] { return std::make_unique<TonemapPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeTonemapPass);
}  // namespace
