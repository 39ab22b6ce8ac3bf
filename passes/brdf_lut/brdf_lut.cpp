// brdf_lut: the split-sum's environment-independent factor: GGX + Smith
// specular albedo as F0 * A + B, A and B tabled over n.v and roughness
// (shaders/brdf_lut.frag). Persistent: computed once per build.
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class BrdfLutPass final : public gl::FullscreenPass {
  uint32_t changedState() const override { return 0; }
};

PassTypeDesc makeBrdfLutPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("brdf_lut", "IBL: the split-sum's scale and bias of F0 over n.v and roughness");
  d.slots = {slot("lut", Access::color_attachment, true, SlotDecl::Load::never,
                  "A (r) and B (g); x: n.v, y: roughness; persistent", {Format::rg16f})};
  d.programs = gl::fullscreenPrograms("brdf_lut.frag", {});
  d.create = [] { return std::make_unique<BrdfLutPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeBrdfLutPass);
}  // namespace
