// specular_cube: the split-sum's pre-filtered environment (Karis 2013):
// level k of the output holds roughness k / (levels - 1), GGX-filtered from
// the environment cube (shaders/specular_cube.frag); the lighting passes read
// it at lod roughness * (levels - 1).
#include <GL/glcorearb.h>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class SpecularCubePass final : public PassInstance {
  void execute(PassContext& ctx) override {
    const uint32_t program = ctx.program(0);
    const uint32_t levels = ibl::levels(ctx, "specular");
    glProgramUniform1f(program, glGetUniformLocation(program, "u_sourceSize"),
                       static_cast<float>(ctx.extent("environment").width));
    glProgramUniform1f(program, glGetUniformLocation(program, "u_sourceLevels"),
                       static_cast<float>(ibl::levels(ctx, "environment")));
    const GLint roughness = glGetUniformLocation(program, "u_roughness");
    ibl::drawFaces(ctx, program, "specular", levels, [&](uint32_t level) {
      glProgramUniform1f(program, roughness, levels > 1 ? float(level) / float(levels - 1) : 0.0f);
    });
  }
  uint32_t changedState() const override { return 0; }
};

PassTypeDesc makeSpecularCubePass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("specular_cube",
                            "IBL: the environment GGX-prefiltered per roughness into a cube's mips (split-sum)");
  d.slots = {slot("environment", Access::sampled, true, SlotDecl::Load::never,
                  "the environment cube with its mip chain (environment_cube)", ibl::cubeFormats()),
             slot("specular", Access::color_attachment, true, SlotDecl::Load::never,
                  "the pre-filtered cube: level k is roughness k / (levels - 1); persistent", ibl::cubeFormats())};
  d.programs = gl::fullscreenPrograms("specular_cube.frag", {{"environment", "u_environment", 0}});
  d.create = [] { return std::make_unique<SpecularCubePass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeSpecularCubePass);
}  // namespace
