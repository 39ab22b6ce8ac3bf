// tiled_deferred: deferred lighting in two compute dispatches. The first
// (shaders/tiled_bin.comp) lists, per bin of tiles at least 64 pixels wide,
// the point lights that reach the bin's frustum, so that the cost of the
// culling below does not grow with the number of lights in the scene at
// constant overlap. In the second, each 16x16 tile of
// the G-buffer finds its depth bounds, culls its bin's lights against its
// frustum into a shared-memory list, marks which of them meet each half row
// of 8 pixels (per 8x8 quarter with far_field; shaders/tiled_deferred.comp
// says why), and shades its pixels with their half row's lights only
// (ambient and the directional light too, unless another pass adds them),
// storing the HDR result with image stores. Same lighting maths and
// defines as deferred_lighting and light_volumes (rgraph/passes/lighting_options.h).
#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/far_field.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/invocation_order.h"
#include "rgraph/passes/light_bins.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

// Shared memory: 4 bytes a listed light (the tile's list) and either, with
// far_field, a bit a light for each of its four quarters' lists, the far
// field's sums and near-light list (< 10 KiB), or, without, 16 bytes a light
// (the lights' view-space spheres) and each of the tile's 2 x tile_size half
// rows' depth bounds and a bit per listed light (tiled_deferred.comp); then
// the counters and depth bounds (< 128 bytes) and the culling's counts (a
// word per run and list, up to 16 runs, and 4 words), within the 32 KiB every
// GL 4.5 device has (GL_MAX_COMPUTE_SHARED_MEMORY_SIZE's minimum), so that
// the program does not depend on the device and validate checks the one that
// runs: 1,344 lights at tile_size 16, 4,944 with far_field.
int64_t tileSharedBytes(int64_t lights, int64_t tile, bool farField) {
  const int64_t rows = 2 * tile, words = (lights + 31) / 32;
  const int64_t lanes = farField ? (tile * tile) & ~int64_t{3} : tile * tile;
  const int64_t cull = 4 * (farField ? 2 : 1) * std::min<int64_t>(lanes, 16) + 16;
  return 128 + cull + 4 * lights +
         (farField ? 10240 + 4 * 4 * words : 16 * lights + rows * 8 + rows * 4 * words);
}

int maxTileLights(const ParamSet& p) {
  const int64_t tile = p.getInt("tile_size");
  const bool farField = p.getBool("far_field");
  int64_t n = std::clamp<int64_t>(p.getInt("max_tile_lights"), 1, 65536);
  // The largest count that fits: the bytes grow by at least 4 a light.
  if (tileSharedBytes(n, tile, farField) > 32768) n = (32768 - tileSharedBytes(0, tile, farField)) / 4;
  while (n > 1 && tileSharedBytes(n, tile, farField) > 32768) --n;
  return static_cast<int>(n);
}

// The bins: at least 64 pixels a side, so that the bin buffer stays small
// (about 2.4 KiB per 64x64 pixels), on storage-buffer binding 1.
lighting::BinGrid binGrid(const ParamSet& p) {
  const int tile = static_cast<int>(p.getInt("tile_size"));
  return {tile, std::max(2, 64 / tile), p.getBool("far_field"), 1};
}

// What both programs share: lighting, G-buffer, tile and far-field defines
// and a test's invocation permutation (the bin program adds the bins' own,
// lighting::binProgram).
std::vector<std::string> commonDefines(const ParamSet& p) {
  std::vector<std::string> defines = lighting::shadingDefines(p);
  defines.push_back("TILE_SIZE=" + std::to_string(p.getInt("tile_size")));
  lighting::addFarFieldDefine(p, defines);
  invocations::addPermuteDefine(p, defines);
  return defines;
}

std::vector<std::string> programDefines(const ParamSet& p, Format target) {
  std::vector<std::string> defines = commonDefines(p);
  for (auto& d : lighting::binDefines(binGrid(p))) defines.push_back(std::move(d));
  defines.push_back("MAX_TILE_LIGHTS=" + std::to_string(maxTileLights(p)));
  defines.push_back(std::string("TARGET_FORMAT=") + lighting::hdrImageQualifier(target));
  return defines;
}

class TiledDeferredPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    tile_ = static_cast<int>(ctx.params().getInt("tile_size"));
    GLint invocations = 0, groupX = 0, groupY = 0;
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 0, &groupX);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, 1, &groupY);
    if (tile_ * tile_ > invocations || tile_ > groupX || tile_ > groupY)
      throw RuntimeError("tiled_deferred pass '" + ctx.passName() + "': tile_size " + std::to_string(tile_) +
                         " needs " + std::to_string(tile_ * tile_) + " invocations per work group; this GL allows " +
                         std::to_string(invocations));
    // programs(): the bin program, then one lighting program per target
    // format (the image format qualifier is a define), in the order of hdrFormats().
    const auto& formats = hdrFormats();
    program_ = ctx.program(1 + (std::find(formats.begin(), formats.end(), ctx.format("color")) - formats.begin()));
    bins_.setup(ctx.program(0), binGrid(ctx.params()), ctx.extent("color"));
    pointLightCount_ = gl::Uniform(program_, "u_pointLightCount");
    ambientAndSun_ = gl::Uniform(program_, "u_ambientAndSun");
    load_ = gl::Uniform(program_, "u_load");
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const Extent size = ctx.extent("color");
    const bool points = ctx.params().getBool("point_lights");
    const int lights = points ? static_cast<int>(scene.pointLightCount()) : 0;
    lighting::bindPointLights(scene, lighting::threshold(ctx.params()));
    shadows::bindInfo(ctx, program_);
    ibl::setUniforms(ctx, program_);
    bins_.build(lights, size);
    glUseProgram(program_);
    pointLightCount_.set(lights);
    ambientAndSun_.set(ctx.params().getBool("ambient_and_sun"));
    load_.set(ctx.loads("color"));
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
  int tile_ = 0;  // tile_size (setup)
  lighting::LightBins bins_;
  gl::Uniform pointLightCount_, ambientAndSun_, load_;
};

PassTypeDesc makeTiledDeferredPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::computeLightingPass(
      "tiled_deferred",
      "Tiled deferred lighting (compute): lights culled per 16x16 tile against its depth bounds, "
      "then per half row of 8 pixels; each pixel shaded with its half row's lights");
  d.params.push_back(ranged("tile_size", ParamType::integer, int64_t{16}, 4, 32,
                            "tile edge in pixels (tile_size^2 invocations per work group)"));
  d.params.push_back(ranged("max_tile_lights", ParamType::integer, int64_t{1024}, 16, 16384,
                            "lights one tile's list holds (shared memory, capped by the GL limit); a tile with "
                            "more shades every light"));
  d.params.push_back(lighting::farFieldParam());
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  shadows::declareReader(d);
  ibl::declareReader(d);
  d.programs = [](const ParamSet& p) {
    std::vector<ShaderProgramSpec> v;
    v.push_back(lighting::binProgram(commonDefines(p), binGrid(p)));
    for (Format target : hdrFormats()) {  // setup() takes the one of the bound target's format
      ShaderProgramSpec s;
      s.comp = "tiled_deferred.comp";
      s.defines = programDefines(p, target);
      s.samplers = lighting::gbufferSamplers();
      s.drawsToAttachments = false;
      shadows::addToProgram(s, p);
      ibl::addToProgram(s, p);
      v.push_back(std::move(s));
    }
    return v;
  };
  d.create = [] { return std::make_unique<TiledDeferredPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeTiledDeferredPass);
}  // namespace
