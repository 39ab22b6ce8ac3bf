// The FXAA plugin: one post-process pass that smooths aliased edges of a
// tone-mapped (LDR) image, after the ideas of FXAA 3.11's quality preset
// (shaders/fxaa.frag says how). It runs after tonemap because its edge test
// is on perceptual luma: in HDR a bright light's edge would dominate every
// threshold. Same-size input and output; pixels away from edges are copied
// unchanged, so flat regions are exact.
#include <GL/glcorearb.h>

#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

const std::vector<Format> kLdrFormats = {Format::rgba8, Format::srgb8_alpha8};

class FxaaPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    contrast_.set(static_cast<float>(p.getNumber("contrast_threshold")));
    relative_.set(static_cast<float>(p.getNumber("relative_threshold")));
    subpixel_.set(static_cast<float>(p.getNumber("subpixel")));
    linearInput_.set(gl::isSrgb(ctx.format("input")));
  }
  ProgramUniform contrast_{this, "u_contrastThreshold"}, relative_{this, "u_relativeThreshold"};
  ProgramUniform subpixel_{this, "u_subpixel"}, linearInput_{this, "u_linearInput"};
};

void registerFxaa(PluginHost& host) {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("fxaa",
      "FXAA (3.11 quality-preset style): edge-directed blend of a tone-mapped image, same size out");
  d.slots = {
      // The edge search and the final blend read between texel centres.
      sampledWith(slot("input", Access::sampled, true, SlotDecl::Load::never,
                       "tone-mapped image (rgba8 or srgb8_alpha8)", kLdrFormats),
                  bilinearClamped()),
      slot("output", Access::color_attachment, true, SlotDecl::Load::never, "the filtered image (input's size)",
           kLdrFormats),
  };
  d.params = {
      ranged("contrast_threshold", ParamType::number, 0.0312, 0.0, 1.0,
             "luma range below which a pixel is left alone (dark areas; 0.0833 faster .. 0.0312 more edges)"),
      ranged("relative_threshold", ParamType::number, 0.125, 0.0, 1.0,
             "luma range, relative to the local maximum, below which a pixel is left alone (0.333 .. 0.063)"),
      ranged("subpixel", ParamType::number, 0.75, 0.0, 1.0, "blending of sub-pixel features (0 off, 1 softest)"),
  };
  d.programs = gl::fullscreenPrograms(host.shaderPath("fxaa.frag"), {{"input", "u_input", 0}});
  d.rules = {sameSizeRule({"output", "input"})};
  d.create = [] { return std::make_unique<FxaaPass>(); };
  host.addPassType(std::move(d));
}

}  // namespace

RGRAPH_PLUGIN("fxaa", registerFxaa)
