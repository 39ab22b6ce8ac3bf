// tiled_deferred: deferred lighting in one compute pass. Each 16x16 tile of
// the G-buffer finds its depth bounds, culls the point lights against its
// frustum into a shared-memory list, and shades its pixels with that list
// only (ambient and the directional light too, unless another pass adds
// them), storing the HDR result with image stores. Same lighting maths and
// defines as deferred_lighting and light_volumes (rgraph/gl/lighting_options.h).
#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/lighting_options.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

const char* imageFormatQualifier(Format f) {
  switch (f) {
    case Format::rgba32f: return "rgba32f";
    case Format::r11g11b10f: return "r11f_g11f_b10f";
    default: return "rgba16f";
  }
}

// Shared memory: the list (4 bytes a light) plus three counters.
int maxTileLights(int requested, GLint sharedBytes) {
  const int fit = std::max(0, (static_cast<int>(sharedBytes) - 64) / 4);
  return std::clamp(std::min(requested, fit), 1, 65536);
}

std::vector<std::string> programDefines(const ParamSet& p, Format target, int tileLights) {
  std::vector<std::string> defines = lighting::defines(p);
  for (auto& def : lighting::gbufferDefines(p)) defines.push_back(std::move(def));
  defines.push_back("TILE_SIZE=" + std::to_string(p.getInt("tile_size", 16)));
  defines.push_back("MAX_TILE_LIGHTS=" + std::to_string(tileLights));
  defines.push_back(std::string("TARGET_FORMAT=") + imageFormatQualifier(target));
  return defines;
}

class TiledDeferredPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (!ctx.gpuScene()) throw RuntimeError("tiled_deferred pass '" + ctx.passName() + "' needs a scene");
    lighting::requireGBuffer(ctx, "tiled_deferred");
    tile_ = static_cast<int>(ctx.params().getInt("tile_size", 16));
    GLint invocations = 0, sharedBytes = 0, groupX = 0, groupY = 0;
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &sharedBytes);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 0, &groupX);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 1, &groupY);
    if (tile_ * tile_ > invocations || tile_ > groupX || tile_ > groupY)
      throw RuntimeError("tiled_deferred pass '" + ctx.passName() + "': tile_size " + std::to_string(tile_) +
                         " needs " + std::to_string(tile_ * tile_) + " invocations per work group; this GL allows " +
                         std::to_string(invocations));
    const int tileLights = maxTileLights(static_cast<int>(ctx.params().getInt("max_tile_lights", 1024)), sharedBytes);
    program_ = ctx.shaders().computeProgram("tiled_deferred.comp",
                                            programDefines(ctx.params(), ctx.format("color"), tileLights));
    countLoc_ = glGetUniformLocation(program_, "u_pointLightCount");
    ambientLoc_ = glGetUniformLocation(program_, "u_ambientAndSun");
    loadLoc_ = glGetUniformLocation(program_, "u_load");
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const Extent size = ctx.extent("color");
    glUseProgram(program_);
    const bool points = ctx.params().getBool("point_lights", true);
    glProgramUniform1i(program_, countLoc_, points ? static_cast<int>(scene.pointLightCount()) : 0);
    glProgramUniform1i(program_, ambientLoc_, ctx.params().getBool("ambient_and_sun", true) ? 1 : 0);
    glProgramUniform1i(program_, loadLoc_, ctx.loads("color") ? 1 : 0);
    scene.bindFrame();
    scene.bindPointLights(lighting::threshold(ctx.params()));
    lighting::bindGBuffer(ctx);
    const GLenum format = ctx.format("color") == Format::rgba32f     ? GL_RGBA32F
                          : ctx.format("color") == Format::r11g11b10f ? GL_R11F_G11F_B10F
                                                                      : GL_RGBA16F;
    glBindImageTexture(0, ctx.texture("color"), 0, GL_FALSE, 0, GL_READ_WRITE, format);
    const GLuint groupsX = (size.width + tile_ - 1) / tile_, groupsY = (size.height + tile_ - 1) / tile_;
    glDispatchCompute(groupsX, groupsY, 1);
    // Whoever reads the target next samples it, blits it, reads it back or draws into it.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
  }

 private:
  uint32_t program_ = 0;
  int tile_ = 16;
  int countLoc_ = -1, ambientLoc_ = -1, loadLoc_ = -1;
};

PassTypeDesc makeTiledDeferredPass() {
  using namespace rgraph::decl;
  PassTypeDesc d;
  d.name = "tiled_deferred";
  d.description = "Tiled deferred lighting (compute): lights culled per 16x16 tile against its depth bounds, "
                  "each pixel shaded with its tile's list";
  d.slots = lighting::gbufferSlots();
  d.slots.push_back(slot("color", Access::storage_write, true, SlotDecl::Load::optional,
                         "HDR lighting target written with image stores; when loaded, the lights are added to it; "
                         "background pixels keep its clear value",
                         {Format::rgba16f, Format::rgba32f, Format::r11g11b10f}));
  d.params = lighting::params();
  d.params.push_back(lighting::layoutParam());
  d.params.push_back(param("point_lights", ParamType::boolean, true, "shade the point lights"));
  d.params.push_back(param("ambient_and_sun", ParamType::boolean, true,
                           "also add ambient and the directional light (false when another pass adds them)"));
  d.params.push_back(ranged("tile_size", ParamType::integer, int64_t{16}, 4, 32,
                            "tile edge in pixels (tile_size^2 invocations per work group)"));
  d.params.push_back(ranged("max_tile_lights", ParamType::integer, int64_t{1024}, 16, 16384,
                            "lights one tile's list holds (shared memory, capped by the GL limit); a tile with "
                            "more shades every light"));
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = lighting::adaptPointLightShading;
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s;
    s.comp = "tiled_deferred.comp";
    s.defines = programDefines(p, Format::rgba16f, static_cast<int>(std::min<int64_t>(p.getInt("max_tile_lights", 1024),
                                                                                     (32768 - 64) / 4)));
    s.samplers = lighting::gbufferSamplers();
    s.drawsToAttachments = false;
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"tiled_deferred.comp"};
  d.create = [] { return std::make_unique<TiledDeferredPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeTiledDeferredPass);
}  // namespace
