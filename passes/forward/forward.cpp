// forward: what a G-buffer cannot hold, drawn over the deferred image with the
// G-buffer's depth (blitted into `depth` beforehand): small cubes marking each
// point light (LearnOpenGL's light boxes) and BLEND materials, back to front,
// lit by every light or, with `clusters` bound, by their cluster's lists
// (forward+, the lists the deferred lighting used too).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/cluster_lists.h"
#include "rgraph/passes/forward_shading.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/light_volume_meshes.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class ForwardPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    markers_ = ctx.params().getBool("markers");
    blend_ = ctx.params().getBool("blend");
    // Programs in the order of the type's programs(): the markers' first when drawn.
    if (markers_) {
      markerProgram_ = ctx.program(0);
      markerSize_ = gl::Uniform(markerProgram_, "u_markerSize");
    }
    if (blend_) surfaces_ = forward::SurfaceDrawer(ctx.program((markers_ ? 1 : 0) + lighting::normalMapVariant(ctx)));
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    gl::bindPassFramebuffer(ctx);
    if (markers_ && scene.pointLightCount() > 0) {
      lighting::bindPointLights(scene, lighting::threshold(ctx.params()));  // (the executor bound the Frame block)
      gl::useProgram(ctx, markerProgram_);
      markerSize_.set(static_cast<float>(ctx.params().getNumber("marker_size")));
      glEnable(GL_DEPTH_TEST);  // function GL_LESS and writes on, as every pass starts (rgraph/pass.h)
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glFrontFace(GL_CCW);  // not part of what the executor resets: set, not assumed (check-hazards, state-scramble)
      light_volumes::Meshes::of(scene).drawCube(ctx.bindings(), scene.pointLightCount());
      glDisable(GL_CULL_FACE);
      glDisable(GL_DEPTH_TEST);
    }
    if (blend_) surfaces_.draw(ctx, /*blended=*/true);
  }
  // Markers and SurfaceDrawer put back what they set and bind through ctx.bindings() (the scene's draws too).
  uint32_t changedState() const override { return 0; }

 private:
  bool markers_ = true, blend_ = true;
  uint32_t markerProgram_ = 0;
  gl::Uniform markerSize_;
  forward::SurfaceDrawer surfaces_;
};

PassTypeDesc makeForwardPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("forward",
      "Forward-rendered light markers and BLEND materials over the deferred image, depth-tested");
  d.slots = {
      slot("color", Access::color_attachment, true, SlotDecl::Load::required, "HDR lighting target to draw over",
           hdrFormats()),
      slot("depth", Access::depth_attachment, true, SlotDecl::Load::required,
           "the scene depth (a blit of the G-buffer depth); markers write it, blended surfaces only test it",
           depthFormats()),
      clusters::readerSlot("light lists a cluster_lights pass built: blended surfaces shade their cluster's lights "
                           "only (forward+); unbound: every light"),
  };
  d.check = clusters::checkReaderSlot;
  d.params = lighting::params();
  d.params.push_back(param("markers", ParamType::boolean, true, "draw a small cube in each point light's colour"));
  d.params.push_back(decl::ranged("marker_size", ParamType::number, 0.125, 0.0, 100.0,
                                  "half extent of a light marker; scene adaptation shrinks it to 1/32 of the scene's "
                                  "bounding radius when the scene is smaller"));
  d.params.push_back(param("blend", ParamType::boolean, true, "draw BLEND materials, lit forward, back to front"));
  d.adapt = [](const SceneFeatures& f, PassAdaptation& a) {
    if (!f.pointLights && a.params.getBool("markers")) {
      a.params.set("markers", false);
      a.notes.push_back("no point lights: no light markers");
    }
    if (f.pointLights && !f.lightMarkers && a.params.getBool("markers")) {
      a.params.set("markers", false);
      a.notes.push_back("the point lights are the glTF file's own (its model draws its lamps): no light markers");
    }
    if (a.params.getBool("markers") && a.params.getNumber("marker_size") > f.markerSizeLimit) {
      a.params.set("marker_size", static_cast<double>(f.markerSizeLimit));
      a.notes.push_back("light markers sized to the scene: half extent " + std::to_string(f.markerSizeLimit) +
                        " (1/32 of its bounding radius)");
    }
    if (!f.blendMaterials && a.params.getBool("blend")) {
      a.params.set("blend", false);
      a.notes.push_back("no BLEND materials: no forward blend");
      a.unbindSlots.push_back(clusters::kSlot);  // markers need no lists: their builder may be culled
      shadows::compileOut(a, "no BLEND materials");  // markers are not shaded: nor are their shadows
    }
    if (!a.params.getBool("markers") && !a.params.getBool("blend")) {
      a.disable = true;
      a.notes.push_back("nothing left to draw forward: pass disabled");
    }
  };
  shadows::declareReader(d);
  ibl::declareReader(d);
  d.programs = [](const ParamSet& p) {
    std::vector<ShaderProgramSpec> v;
    if (p.getBool("markers")) v.push_back(programSpec("light_marker.vert", "light_marker.frag"));
    if (p.getBool("blend"))
      for (auto& s : forward::programs(p, /*blendsSourceAlpha=*/true)) v.push_back(std::move(s));
    return v;
  };
  d.needsScene = true;
  d.create = [] { return std::make_unique<ForwardPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeForwardPass);
}  // namespace
