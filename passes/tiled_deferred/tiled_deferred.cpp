// tiled_deferred: deferred lighting in one compute pass. Each 16x16 tile of
// the G-buffer finds its depth bounds, culls the point lights against its
// frustum into a shared-memory list, refines that list per 8x8 quarter
// (shaders/tiled_deferred.comp says why), and shades its pixels with their
// quarter's list only (ambient and the directional light too, unless another pass adds
// them), storing the HDR result with image stores. Same lighting maths and
// defines as deferred_lighting and light_volumes (rgraph/passes/lighting_options.h).
#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

// Shared memory: the tile's list and its four quarters' lists (each a subset
// of the tile's: 5 x 4 bytes a light) plus the counters and depth bounds,
// within the 32 KiB every GL 4.5 device has (GL_MAX_COMPUTE_SHARED_MEMORY_SIZE's
// minimum), so that the program does not depend on the device and validate
// checks the one that runs.
int maxTileLights(const ParamSet& p) {
  constexpr int64_t kFit = (32768 - 128) / 20;
  return static_cast<int>(std::clamp<int64_t>(std::min(p.getInt("max_tile_lights", 1024), kFit), 1, 65536));
}

std::vector<std::string> programDefines(const ParamSet& p, Format target) {
  std::vector<std::string> defines = lighting::shadingDefines(p);
  defines.push_back("TILE_SIZE=" + std::to_string(p.getInt("tile_size", 16)));
  defines.push_back("MAX_TILE_LIGHTS=" + std::to_string(maxTileLights(p)));
  defines.push_back(std::string("TARGET_FORMAT=") + lighting::hdrImageQualifier(target));
  return defines;
}

class TiledDeferredPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    tile_ = static_cast<int>(ctx.params().getInt("tile_size", 16));
    GLint invocations = 0, groupX = 0, groupY = 0;
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 0, &groupX);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 1, &groupY);
    if (tile_ * tile_ > invocations || tile_ > groupX || tile_ > groupY)
      throw RuntimeError("tiled_deferred pass '" + ctx.passName() + "': tile_size " + std::to_string(tile_) +
                         " needs " + std::to_string(tile_ * tile_) + " invocations per work group; this GL allows " +
                         std::to_string(invocations));
    // programs() has one program per target format (the image format
    // qualifier is a define), in the order of hdrFormats().
    const auto& formats = lighting::hdrFormats();
    program_ = ctx.program(std::find(formats.begin(), formats.end(), ctx.format("color")) - formats.begin());
    pointLightCount_ = gl::Uniform(program_, "u_pointLightCount");
    ambientAndSun_ = gl::Uniform(program_, "u_ambientAndSun");
    load_ = gl::Uniform(program_, "u_load");
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const Extent size = ctx.extent("color");
    glUseProgram(program_);
    const bool points = ctx.params().getBool("point_lights", true);
    pointLightCount_.set(points ? static_cast<int>(scene.pointLightCount()) : 0);
    ambientAndSun_.set(ctx.params().getBool("ambient_and_sun", true));
    load_.set(ctx.loads("color"));
    scene.bindFrame();
    scene.bindPointLights(lighting::threshold(ctx.params()));
    glBindImageTexture(0, ctx.texture("color"), 0, GL_FALSE, 0, GL_READ_WRITE,
                       lighting::hdrImageFormat(ctx.format("color")));
    const GLuint groupsX = (size.width + tile_ - 1) / tile_, groupsY = (size.height + tile_ - 1) / tile_;
    glDispatchCompute(groupsX, groupsY, 1);
    // No memory barrier here: the executor issues the bits whoever touches
    // the target next needs, from the slot's declared access (storage_write).
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
  }

 private:
  uint32_t program_ = 0;
  int tile_ = 16;
  gl::Uniform pointLightCount_, ambientAndSun_, load_;
};

PassTypeDesc makeTiledDeferredPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::computeLightingPass(
      "tiled_deferred",
      "Tiled deferred lighting (compute): lights culled per 16x16 tile against its depth bounds, "
      "each pixel shaded with its tile's list");
  d.params.push_back(ranged("tile_size", ParamType::integer, int64_t{16}, 4, 32,
                            "tile edge in pixels (tile_size^2 invocations per work group)"));
  d.params.push_back(ranged("max_tile_lights", ParamType::integer, int64_t{1024}, 16, 16384,
                            "lights one tile's list holds (shared memory, capped by the GL limit); a tile with "
                            "more shades every light"));
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.programs = [](const ParamSet& p) {
    std::vector<ShaderProgramSpec> v;
    for (Format target : lighting::hdrFormats()) {  // setup() takes the one of the bound target's format
      ShaderProgramSpec s;
      s.comp = "tiled_deferred.comp";
      s.defines = programDefines(p, target);
      s.samplers = lighting::gbufferSamplers();
      s.drawsToAttachments = false;
      v.push_back(std::move(s));
    }
    return v;
  };
  d.create = [] { return std::make_unique<TiledDeferredPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeTiledDeferredPass);
}  // namespace
