// cluster_lights: builds the clustered light lists (rgraph/passes/cluster_lists.h)
// into a graph buffer, once a frame, for every pass that shades with them:
// clustered_deferred on the G-buffer, forward and forward_lit on the surfaces
// they draw (forward+: blended surfaces lit by the lists instead of every
// light). The lists depend on the camera, the lights and the cut-off only,
// not on depth, so no pass has to run before it.
#include <GL/glcorearb.h>

#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/cluster_lists.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class ClusterLightsPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override { builder_ = clusters::Builder(ctx.program(0)); }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    // The grid covers the viewport (the Frame block's, the output size), as
    // the readers index it.
    builder_.build(scene, ctx.buffer(clusters::kSlot), clusters::grid(ctx.params()), ctx.outputExtent(),
                   static_cast<int>(scene.pointLightCount()), lighting::threshold(ctx.params()), /*barrier=*/false);
  }

 private:
  clusters::Builder builder_;
};

PassTypeDesc makeClusterLightsPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("cluster_lights",
      "Clustered light lists (compute): per view-space cluster (screen tile x exponential depth slice), the point "
      "lights whose cut-off sphere touches it, into a buffer that clustered_deferred, forward and forward_lit read");
  d.slots = {slot(clusters::kSlot, Access::storage_write, true, SlotDecl::Load::never,
                  "buffer the lists go into (a header, a count per cluster, max_cluster_lights indices per "
                  "cluster: see the check's message for the bytes an output size needs)")};
  // Only the threshold: lists of lights cut at it. A pass reading them shades
  // with its own cut-off, which should be the same (a lower one loses the
  // light of the lights the lists leave out; a higher one only costs time).
  for (auto& p : lighting::params())
    if (p.name == "threshold") d.params.push_back(std::move(p));
  for (auto& p : clusters::gridParams()) d.params.push_back(std::move(p));
  d.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    clusters::checkBuilderSlot(ctx, checks, clusters::kSlot);
  };
  d.programs = [](const ParamSet& p) { return std::vector<ShaderProgramSpec>{clusters::buildProgram(p)}; };
  d.needsScene = true;
  d.create = [] { return std::make_unique<ClusterLightsPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeClusterLightsPass);
}  // namespace
