// tonemap: HDR lighting target -> the 8-bit output (exposure, Reinhard or
// ACES, sRGB transfer).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class TonemapPass final : public gl::FullscreenPass {
  // Per frame: passes with the same program share it. (The executor leaves
  // GL_FRAMEBUFFER_SRGB on, so an srgb8_alpha8 output encodes on write.)
  void update(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const std::string op = p.getString("operator");
    exposure_.set(static_cast<float>(p.getNumber("exposure")));
    operator_.set(op == "reinhard" ? 0 : op == "aces" ? 1 : 2);
    encodeSrgb_.set(!gl::isSrgb(ctx.format("output")));  // a linear rgba8 target gets the curve here
    gamma_.set(static_cast<float>(p.getNumber("gamma")));
  }
  uint32_t changedState() const override { return 0; }  // uniforms only
  ProgramUniform exposure_{this, "u_exposure"}, operator_{this, "u_operator"};
  ProgramUniform encodeSrgb_{this, "u_encodeSrgb"}, gamma_{this, "u_gamma"};
};

PassTypeDesc makeTonemapPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("tonemap", "HDR to the display: exposure, Reinhard or ACES, sRGB transfer");
  d.slots = {
      slot("hdr", Access::sampled, true, SlotDecl::Load::never, "the HDR image", hdrFormats()),
      slot("output", Access::color_attachment, true, SlotDecl::Load::never,
           "the display image (srgb8_alpha8 encodes on write; rgba8 gets the curve in the shader)",
           {Format::rgba8, Format::srgb8_alpha8}),
  };
  d.params = {
      param("operator", ParamType::enumeration, std::string("aces"), "tone curve (none: clamp to 1)",
            {"reinhard", "aces", "none"}),
      ranged("exposure", ParamType::number, 1.0, 0.0, 1000.0, "multiplies the HDR colour before the curve"),
      ranged("gamma", ParamType::number, 0.0, 0.0, 5.0, "0: the exact sRGB curve; otherwise pow(c, 1/gamma)"),
  };
  d.programs = gl::fullscreenPrograms("tonemap.frag", {{"hdr", "u_hdr", 0}});
  d.rules = {sameSizeRule({"hdr", "output"})};
  d.create = [] { return std::make_unique<TonemapPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeTonemapPass);
}  // namespace
