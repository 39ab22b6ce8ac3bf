// irradiance_cube: the diffuse half of image-based lighting: E/pi of the
// environment cube around each direction (shaders/irradiance_cube.frag),
// into a small cube (32 squared is plenty: irradiance varies slowly).
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class IrradianceCubePass final : public PassInstance {
  void execute(PassContext& ctx) override {
    const uint32_t program = ctx.program(0);
    // The source level whose faces are 8 texels wide (11 degrees a texel):
    // the 64 x 16 grid (5.6 degrees apart) takes two samples a texel, so a
    // small bright source (a sun) is neither missed nor hit twice.
    const float width = static_cast<float>(ctx.extent("environment").width);
    const float lod = std::clamp(std::log2(width / 8.0f), 0.0f, float(ibl::levels(ctx, "environment") - 1));
    glProgramUniform1f(program, glGetUniformLocation(program, "u_sourceLod"), lod);
    ibl::drawFaces(ctx, program, "irradiance", 1);
  }
  uint32_t changedState() const override { return 0; }
};

PassTypeDesc makeIrradianceCubePass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("irradiance_cube", "IBL: the environment's irradiance / pi into a cube (diffuse ambient)");
  d.slots = {slot("environment", Access::sampled, true, SlotDecl::Load::never,
                  "the environment cube with its mip chain (environment_cube)", ibl::cubeFormats()),
             slot("irradiance", Access::color_attachment, true, SlotDecl::Load::never,
                  "the irradiance cube (level 0 written); persistent", ibl::cubeFormats())};
  d.programs = gl::fullscreenPrograms("irradiance_cube.frag", {{"environment", "u_environment", 0}});
  d.create = [] { return std::make_unique<IrradianceCubePass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeIrradianceCubePass);
}  // namespace
