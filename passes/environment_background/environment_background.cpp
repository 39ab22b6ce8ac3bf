// environment_background: the environment where nothing was drawn (depth 1),
// after lighting and before tone mapping. Disabled by scene adaptation when
// the scene has no environment (the target keeps its clear colour).
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class EnvironmentBackgroundPass final : public gl::FullscreenPass {
  // Unadapted, a scene without an environment keeps the target's clear colour.
  void execute(PassContext& ctx) override {
    if (ctx.scene() && ctx.scene()->environment) gl::FullscreenPass::execute(ctx);
  }
  uint32_t changedState() const override { return 0; }
};

PassTypeDesc makeEnvironmentBackgroundPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("environment_background", "IBL: the environment drawn where depth is 1 (the background)");
  d.slots = {slot("environment", Access::sampled, true, SlotDecl::Load::never,
                  "the environment cube (environment_cube)", ibl::cubeFormats()),
             slot("depth", Access::sampled, true, SlotDecl::Load::never, "depth of everything drawn", depthFormats()),
             slot("color", Access::color_attachment, true, SlotDecl::Load::required,
                  "the HDR target, drawn over where depth is 1", hdrFormats())};
  d.programs = gl::fullscreenPrograms("environment_background.frag",
                                      {{"environment", "u_environment", 0}, {"depth", "u_depth", 1}});
  d.rules = {sameSizeRule({"depth", "color"})};
  d.needsScene = true;
  d.adapt = [](const SceneFeatures& f, PassAdaptation& a) {
    if (f.environment) return;
    a.disable = true;
    a.notes.push_back("no environment: the background keeps the target's clear colour");
  };
  d.create = [] { return std::make_unique<EnvironmentBackgroundPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeEnvironmentBackgroundPass);
}  // namespace
