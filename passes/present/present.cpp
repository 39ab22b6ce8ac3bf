// present: copies/converts a colour image into the output image (rgba8 or
// srgb8_alpha8), optionally applying the sRGB transfer for a linear rgba8 target.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class PresentPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const Extent e = ctx.framebufferExtent();
    sameSize_.set(ctx.extent("src") == e);
    gamma_.set(ctx.params().getBool("gamma") && !gl::isSrgb(ctx.format("dst")));
    resolution_.set(static_cast<float>(e.width), static_cast<float>(e.height));
  }
  ProgramUniform sameSize_{this, "u_same_size"}, gamma_{this, "u_gamma"}, resolution_{this, "u_resolution"};
};

PassTypeDesc makePresentPass() {
  PassTypeDesc d = decl::passType("present", "Copies a colour image into the output image, converting to 8 bits");
  d.slots = {
      decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "the image to show"),
      decl::slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the output image",
               {Format::rgba8, Format::srgb8_alpha8}),
  };
  d.params = {decl::param("gamma", ParamType::boolean, false, "apply the sRGB transfer when the target is linear rgba8")};
  d.programs = gl::fullscreenPrograms("present.frag", {{"src", "src", 0}});
  PassRule colour;
  colour.text = "src is a colour image, not depth";
  colour.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    if (auto f = ctx.format("src"); f && isDepthFormat(*f))
      checks.slotError("src", "src has a depth format (" + std::string(formatName(*f)) + "); present shows colour images");
  };
  d.rules = {colour};
  d.create = [] { return std::make_unique<PresentPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makePresentPass);
}  // namespace
