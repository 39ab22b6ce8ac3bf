// light_volumes: each point light drawn as an instanced sphere scaled to its
// radius, each spot light as a cone of that radius and its outer angle
// (light_volume.vert), shading only the pixels the light can reach, added
// into the lighting target. Front faces are culled (the far side of each
// volume is drawn) so a camera inside a volume still sees its light; the
// depth test keeps only pixels whose surface lies in front of that far side.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/light_volume_meshes.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class LightVolumesPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    program_ = ctx.program(0);
    volumeScale_ = gl::Uniform(program_, "u_volumeScale");
    firstLight_ = gl::Uniform(program_, "u_firstLight");
    spotVolumes_ = gl::Uniform(program_, "u_spotVolumes");
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    gl::bindPassFramebuffer(ctx);
    gl::useProgram(ctx, program_);
    lighting::bindPointLights(scene, lighting::threshold(ctx.params()));  // (the executor bound the Frame block)
    shadows::bindInfo(ctx, program_);

    const std::string cull = ctx.params().getString("cull");
    glEnable(GL_CULL_FACE);
    glCullFace(cull == "back" ? GL_BACK : GL_FRONT);
    glFrontFace(GL_CCW);  // not part of what the executor resets: set, not assumed (check-hazards, state-scramble)
    if (ctx.bound("depth_test")) {
      glEnable(GL_DEPTH_TEST);
      // Front culled: the far side of the sphere must lie behind (or at) the
      // surface. Back culled: the near side must lie in front of it.
      glDepthFunc(cull == "back" ? GL_LEQUAL : GL_GEQUAL);
    }
    glDepthMask(GL_FALSE);
    // A volume reaching past the far plane would be clipped away and lose
    // its light: clamp depth instead.
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    // The buffer lists the point lights, then the spot lights.
    const uint32_t spots = scene.spotLightCount(), points = scene.pointLightCount() - spots;
    const light_volumes::Meshes& meshes = light_volumes::Meshes::of(scene);
    volumeScale_.set(meshes.icosphereScale());
    firstLight_.set(0);
    spotVolumes_.set(0);
    meshes.drawIcosphere(ctx.bindings(), points);
    if (spots > 0) {
      volumeScale_.set(meshes.spotVolumeScale());
      firstLight_.set(static_cast<int>(points));
      spotVolumes_.set(1);
      meshes.drawSpotVolume(ctx.bindings(), spots);
    }
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
  }
  // Every group put back as it started; binds through ctx.bindings() (the scene's draws too).
  uint32_t changedState() const override { return 0; }

 private:
  uint32_t program_ = 0;
  gl::Uniform volumeScale_, firstLight_, spotVolumes_;
};

PassTypeDesc makeLightVolumesPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::gbufferReader(
      "light_volumes", "Point lights as instanced spheres scaled to their radius, spot lights as cones, added into the lighting target");
  d.slots.push_back(slot("depth_test", Access::depth_attachment_read, false, SlotDecl::Load::never,
                         "scene depth to test volumes against (read-only; a copy when the layout samples depth)",
                         depthFormats()));
  d.slots.push_back(slot("color", Access::color_attachment, true, SlotDecl::Load::required,
                         "HDR lighting target the lights are added to", hdrFormats()));
  d.params = lighting::params(5.0 / 256.0, /*allowNoCutoff=*/false);
  d.params.push_back(lighting::layoutParam());
  d.params.push_back(param("cull", ParamType::enumeration, std::string("front"),
                           "faces culled: front (correct with the camera inside a volume) or back (loses lights "
                           "whose volume contains the camera; kept to show why)",
                           {"front", "back"}));
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = [](const SceneFeatures& f, PassAdaptation& a) {
    if (!f.pointLights) {
      a.disable = true;
      a.notes.push_back("no point lights: no light volumes (pass disabled, its target passes through)");
      return;
    }
    lighting::adaptGBuffer(f, a);
  };
  shadows::declareReader(d);
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s =
        programSpec("light_volume.vert", "light_volume.frag", lighting::shadingDefines(p), lighting::gbufferSamplers());
    shadows::addToProgram(s, p);
    return std::vector{std::move(s)};
  };
  d.create = [] { return std::make_unique<LightVolumesPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeLightVolumesPass);
}  // namespace
