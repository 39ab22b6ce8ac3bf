// forward_lit: the classic forward renderer. Every surface shades every light
// per fragment; blended materials follow, back to front. It is the reference
// the deferred pipelines are checked against, and the baseline they must beat.
// With `clusters` bound (a cluster_lights pass's lists) it is forward+: each
// fragment shades only the lights listed for its cluster.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/cluster_lists.h"
#include "rgraph/passes/forward_shading.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/passes/velocity.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class ForwardLitPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    surfaces_ = forward::SurfaceDrawer(ctx.program(lighting::normalMapVariant(ctx)));
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    const float one = 1.0f;
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_DEPTH, 0, &one);
    if (ctx.bound("velocity")) {  // the background keeps 0, as in the geometry pass
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 1, zero);
    }
    surfaces_.draw(ctx, /*blended=*/false);
    if (ctx.params().getBool("blend")) surfaces_.draw(ctx, /*blended=*/true);
  }

 private:
  forward::SurfaceDrawer surfaces_;
};

PassTypeDesc makeForwardLitPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("forward_lit",
      "Classic forward renderer: every light per fragment (the reference and the baseline)");
  d.slots = {
      slot("color", Access::color_attachment, true, SlotDecl::Load::optional,
           "HDR target; background keeps its clear value", hdrFormats()),
      slot("depth", Access::depth_attachment, true, SlotDecl::Load::never, "depth buffer (cleared here)",
           depthFormats()),
      velocity::slot(),
      clusters::readerSlot("light lists a cluster_lights pass built: each fragment shades its cluster's lights only "
                           "(forward+); unbound: every light"),
  };
  d.params = lighting::params();
  d.params.push_back(param("blend", ParamType::boolean, true, "also draw BLEND materials, back to front"));
  d.params.push_back(velocity::param());
  d.rules = {velocity::rule()};
  d.check = clusters::checkReaderSlot;
  d.adapt = [](const SceneFeatures& f, PassAdaptation& a) {
    if (!f.blendMaterials && a.params.getBool("blend")) {
      a.params.set("blend", false);
      a.notes.push_back("no BLEND materials: opaque surfaces only");
    }
  };
  shadows::declareReader(d);
  ibl::declareReader(d);
  d.programs = [](const ParamSet& p) { return forward::programs(p, p.getBool("blend")); };
  d.needsScene = true;
  d.create = [] { return std::make_unique<ForwardLitPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeForwardLitPass);
}  // namespace
