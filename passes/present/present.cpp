// present: copies/converts a colour image into the output image (rgba8 or
// srgb8_alpha8), optionally applying the sRGB transfer for a linear rgba8 target.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class PresentPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (gl::isDepth(ctx.format("src")))
      throw RuntimeError("present pass '" + ctx.passName() + "': src has a depth format (" +
                         std::string(formatName(ctx.format("src"))) + ")");
    program_ = ctx.shaders().program("fullscreen.vert", "present.frag");
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
    sameSize_ = ctx.extent("src") == ctx.framebufferExtent();
    bool gamma = ctx.params().getBool("gamma", false) && !gl::isSrgb(ctx.format("dst"));
    glProgramUniform1i(program_, glGetUniformLocation(program_, "src"), 0);
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_same_size"), sameSize_ ? 1 : 0);
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_gamma"), gamma ? 1 : 0);
    Extent e = ctx.framebufferExtent();
    glProgramUniform2f(program_, glGetUniformLocation(program_, "u_resolution"), static_cast<float>(e.width),
                       static_cast<float>(e.height));
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glUseProgram(program_);
    glBindTextureUnit(0, ctx.texture("src"));
    triangle_->draw();
    glBindTextureUnit(0, 0);
  }

 private:
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
  bool sameSize_ = true;
};

PassTypeDesc makePresentPass() {
  PassTypeDesc d;
  d.name = "present";
  d.description = "Copies a colour image into the output image, converting to 8 bits";
  d.slots = {
      decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "the image to show"),
      decl::slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the output image (rgba8 or srgb8_alpha8)",
               {Format::rgba8, Format::srgb8_alpha8}),
  };
  d.params = {decl::param("gamma", ParamType::boolean, false, "apply the sRGB transfer when the target is linear rgba8")};
  d.programs = [](const ParamSet&) {
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = "present.frag";
    s.samplers = {{"src", "src", -1}};  // setup() sets the uniform to unit 0
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"fullscreen.vert", "present.frag"};
  d.create = [] { return std::make_unique<PresentPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makePresentPass);
}  // namespace
