// vignette: a post effect as an rgraph plugin. One pass type, "vignette",
// with one parameter ("strength"), one sampled input ("src") and one colour
// output ("dst") of the same size. See README.md.
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

// One instance per pass in a running pipeline. gl::FullscreenPass does the
// rest: it takes the program the declaration names (built by rgraph, which
// also binds "src" to unit 0), binds the pass's framebuffer ("dst" is
// attached) and draws a fullscreen triangle every frame.
class VignettePass final : public gl::FullscreenPass {
  // Every frame, before the draw: the uniform from the pass's parameter.
  void update(PassContext& ctx) override { strength_.set(static_cast<float>(ctx.params().getNumber("strength", 0.6))); }
  // Looked up once, when the pass is set up (not every frame).
  ProgramUniform strength_{this, "u_strength"};
};

// Called once when rgraph loads the plugin: declare the pass type.
void registerTypes(PluginHost& host) {
  using namespace rgraph::decl;
  PassTypeDesc d;
  d.name = "vignette";  // the config's "type"
  d.description = "Darkens the image towards its corners";
  d.slots = {
      slot("src", Access::sampled, true, SlotDecl::Load::never, "image to darken (any colour format)"),
      slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the darkened image"),
  };
  d.params = {ranged("strength", ParamType::number, 0.6, 0.0, 1.0, "darkening at the corners (0: none, 1: black)")};
  // The program: rgraph's fullscreen.vert + shaders/vignette.frag (its absolute
  // path where rgraph_add_plugin put it), whose sampler u_src reads "src" on
  // unit 0. `rgraph validate` checks exactly this program against the config.
  d.programs = gl::fullscreenPrograms(host.shaderPath("vignette.frag"), {{"src", "u_src", 0}});
  // Checked before anything runs, by validate and render alike; `rgraph passes`
  // prints the sentence.
  d.rules = {sameSizeRule({"src", "dst"})};
  d.create = [] { return std::make_unique<VignettePass>(); };
  host.addPassType(std::move(d));
}

}  // namespace

// Exports rgraph_plugin_abi_version() and rgraph_plugin_register().
RGRAPH_PLUGIN("vignette", registerTypes)
