// gbuffer_view: shows one G-buffer target (the PBR chapter's debug views):
// position with a log mapping, normal as |n| or n * 0.5 + 0.5, albedo,
// specular, metallic, roughness, linear depth.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

const std::vector<std::string> kViews = {"position", "normal_abs", "normal", "albedo",
                                         "specular", "metallic",   "roughness", "depth"};

class GBufferViewPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const std::string view = ctx.params().getString("view");
    int mode = 3;
    for (size_t i = 0; i < kViews.size(); ++i)
      if (kViews[i] == view) mode = static_cast<int>(i);
    mode_.set(mode);  // (the executor bound the Frame block)
  }
  ProgramUniform mode_{this, "u_mode"};
};

PassTypeDesc makeGBufferViewPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::gbufferReader(
      "gbuffer_view",
      "Debug view of one G-buffer target (position, normal, albedo, specular, metallic, roughness, depth)");
  d.slots.push_back(slot("color", Access::color_attachment, true, SlotDecl::Load::never, "the view"));
  d.params = {param("view", ParamType::enumeration, std::string("albedo"), "which target to show", kViews),
              lighting::layoutParam()};
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.programs = [](const ParamSet& p) {
    return std::vector{
        gl::fullscreenProgram("gbuffer_view.frag", lighting::gbufferSamplers(), lighting::gbufferDefines(p))};
  };
  d.create = [] { return std::make_unique<GBufferViewPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeGBufferViewPass);
}  // namespace
