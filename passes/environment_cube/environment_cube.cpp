// environment_cube: the scene's environment (Scene::environment: a uniform
// colour, the procedural sky or an equirectangular .hdr) into level 0 of a
// cube map, the rest of its chain by glGenerateMipmap (the pre-filters read
// it filtered). Its output is meant to be persistent (docs/ibl.md): the
// executor runs the pass on the first frame and after the environment changes.
#include <GL/glcorearb.h>

#include <cmath>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace {
using namespace rgraph;

class EnvironmentCubePass final : public PassInstance {
  void execute(PassContext& ctx) override {
    const uint32_t program = ctx.program(0);
    Environment env;
    env.color = glm::vec3(0.0f);  // no environment: black
    if (ctx.scene() && ctx.scene()->environment) env = *ctx.scene()->environment;
    auto u = [&](const char* name) { return glGetUniformLocation(program, name); };
    glProgramUniform1i(program, u("u_kind"), static_cast<GLint>(env.kind));
    glProgramUniform1f(program, u("u_intensity"), env.intensity);
    glProgramUniform3f(program, u("u_color"), env.color.x, env.color.y, env.color.z);
    const glm::vec3 sun = glm::normalize(env.sunDirection);
    glProgramUniform3f(program, u("u_sunDirection"), sun.x, sun.y, sun.z);
    glProgramUniform3f(program, u("u_sunColor"), env.sunColor.x, env.sunColor.y, env.sunColor.z);
    glProgramUniform1f(program, u("u_sunRadius"), glm::radians(env.sunRadiusDeg));
    glProgramUniform3f(program, u("u_zenith"), env.zenith.x, env.zenith.y, env.zenith.z);
    glProgramUniform3f(program, u("u_horizon"), env.horizon.x, env.horizon.y, env.horizon.z);
    glProgramUniform3f(program, u("u_ground"), env.ground.x, env.ground.y, env.ground.z);
    // The .hdr image, uploaded only when the pass runs (the environment changed).
    equirect_ = {};
    if (env.kind == Environment::Kind::hdr && env.width > 0) {
      equirect_ = gl::createTexture(GL_TEXTURE_2D);
      const auto w = static_cast<GLsizei>(env.width), h = static_cast<GLsizei>(env.height);
      glTextureStorage2D(equirect_.id(), 1, GL_RGB32F, w, h);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTextureSubImage2D(equirect_.id(), 0, 0, 0, w, h, GL_RGB, GL_FLOAT, env.rgb.data());
      glTextureParameteri(equirect_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(equirect_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(equirect_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTextureParameteri(equirect_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glBindTextureUnit(0, equirect_.id());
    ibl::drawFaces(ctx, program, "cube", 1);
    glBindTextureUnit(0, 0);
    glGenerateTextureMipmap(ctx.texture("cube"));
  }
  uint32_t changedState() const override { return 0; }  // binds through ctx.bindings(); uniforms and textures
  gl::Texture equirect_;
};

PassTypeDesc makeEnvironmentCubePass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("environment_cube",
                            "IBL: the scene's environment (colour, sky or .hdr) into a cube map and its mip chain");
  d.slots = {slot("cube", Access::color_attachment, true, SlotDecl::Load::never,
                  "the environment cube (\"cube\": true, \"mips\": \"full\"); persistent", ibl::cubeFormats())};
  d.programs = [](const ParamSet&) {
    ShaderProgramSpec s = gl::fullscreenProgram("environment_cube.frag");
    s.ownSamplers = {"u_equirect"};
    return std::vector<ShaderProgramSpec>{s};
  };
  d.needsScene = true;
  d.create = [] { return std::make_unique<EnvironmentCubePass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeEnvironmentCubePass);
}  // namespace
