// vignette: a post effect as an rgraph plugin. One pass type, "vignette",
// with one parameter ("strength"), one sampled input ("src") and one colour
// output ("dst") of the same size. See README.md.
#include <GL/glcorearb.h>  // GL 4.5 core; rgraph::rgraph defines GL_GLEXT_PROTOTYPES

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

// One instance per pass in a running pipeline.
class VignettePass final : public PassInstance {
 public:
  explicit VignettePass(std::string frag) : frag_(std::move(frag)) {}

  // Once the pipeline's textures exist (again after a resize): check the
  // bindings, build GL objects.
  void setup(PassContext& ctx) override {
    if (ctx.extent("src") != ctx.framebufferExtent())
      throw RuntimeError("vignette pass '" + ctx.passName() + "': 'src' and 'dst' must have the same size");
    program_ = ctx.shaders().program("fullscreen.vert", frag_);  // rgraph's own vertex shader
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
  }

  // Every frame. ctx.framebuffer() has "dst" attached.
  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glUseProgram(program_);
    glProgramUniform1f(program_, glGetUniformLocation(program_, "u_strength"),
                       static_cast<float>(ctx.params().getNumber("strength", 0.6)));
    glBindTextureUnit(0, ctx.texture("src"));
    triangle_->draw();
  }

 private:
  std::string frag_;
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

// Called once when rgraph loads the plugin: declare the pass type.
void registerTypes(PluginHost& host) {
  using namespace rgraph::decl;
  // Absolute path of shaders/vignette.frag where rgraph_add_plugin put it.
  const std::string frag = host.shaderPath("vignette.frag");

  PassTypeDesc d;
  d.name = "vignette";  // the config's "type"
  d.description = "Darkens the image towards its corners";
  d.slots = {
      slot("src", Access::sampled, true, SlotDecl::Load::never, "image to darken (any colour format)"),
      slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "result (same size as src)"),
  };
  d.params = {ranged("strength", ParamType::number, 0.6, 0.0, 1.0, "darkening at the corners (0: none, 1: black)")};
  d.shaders = {"fullscreen.vert", frag};  // what `rgraph validate` checks
  d.create = [frag] { return std::make_unique<VignettePass>(frag); };
  host.addPassType(std::move(d));
}

}  // namespace

// Exports rgraph_plugin_abi_version() and rgraph_plugin_register().
RGRAPH_PLUGIN("vignette", registerTypes)
