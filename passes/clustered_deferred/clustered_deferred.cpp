// clustered_deferred: deferred lighting over view-space clusters, in compute
// dispatches. The first ones build, per cluster (a screen tile times an
// exponential depth slice, shaders/include/clusters.glsl), the list of point
// lights whose sphere touches the cluster's box (rgraph/passes/cluster_lists.h),
// into a storage buffer the pass owns: the light bins (rgraph/passes/light_bins.h)
// list the lights near each 64-pixel bin, then each tile culls its bin's list
// (not every light: flat in the light count) against its clusters, each
// bounded by its pixels' depths (a cluster without pixels lists nothing). With its `clusters` slot bound to the
// buffer a cluster_lights pass wrote, it skips that and reads those lists
// (built once a frame for this pass and forward+). The last shades every
// pixel with its cluster's list and stores the HDR result. Unlike
// tiled_deferred, a tile's pixels at very different depths (a pillar over a
// far wall) do not share one list spanning both. Same lighting maths and
// defines as deferred_lighting, light_volumes and tiled_deferred
// (rgraph/passes/lighting_options.h).
// A cluster reached by more than max_cluster_lights lights: its count keeps
// the true number, the buffer's header counts the cluster, and its pixels
// shade every light (overflow "shade_all", correct and slow) or only the
// listed ones ("truncate", wrong: for showing that clusters overflow).
#include <GL/glcorearb.h>

#include <algorithm>
#include <string>

#include "rgraph/format_sets.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/ibl.h"
#include "rgraph/passes/cluster_lists.h"
#include "rgraph/passes/far_field.h"
#include "rgraph/passes/invocation_order.h"
#include "rgraph/passes/light_bins.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

constexpr int kShadeGroup = 8;  // clustered_deferred.comp's local_size_x and _y
constexpr uint32_t kFarFieldBinding = 3;  // include/cluster_far_field.glsl's buffer
constexpr int kFarFieldRecord = 4 + 16 * 12;  // its CLUSTER_FAR_RECORD (uints per cluster)

bool farField(const ParamSet& p) { return p.getBool("far_field"); }

// The light bins the pass's own list build culls (and its far field takes
// the far lights from): one cluster tile, or as many as make 64 pixels, a
// side (on binding 2: the lists are on 1).
lighting::BinGrid binGrid(const ParamSet& p) {
  const int tile = clusters::grid(p).tileSize;
  return {tile, std::max(1, (64 + tile - 1) / tile), farField(p), 2};
}

// Lighting, G-buffer and far-field defines and a test's invocation
// permutation: every program but the list build (clusters::buildProgram
// adds the permutation there).
std::vector<std::string> shadingDefines(const ParamSet& p) {
  std::vector<std::string> defines = lighting::shadingDefines(p);
  lighting::addFarFieldDefine(p, defines);
  invocations::addPermuteDefine(p, defines);
  return defines;
}

class ClusteredDeferredPass final : public PassInstance {
 public:
  ~ClusteredDeferredPass() override {
    if (buffer_) glDeleteBuffers(1, &buffer_);
    if (farFields_) glDeleteBuffers(1, &farFields_);
  }

  void setup(PassContext& ctx) override {
    // programs(): the build program, then one shading program per target
    // format in the order of hdrFormats() (the image format is a define).
    builder_ = clusters::Builder(ctx.program(0));
    const auto& formats = hdrFormats();
    shade_ = ctx.program(1 + (std::find(formats.begin(), formats.end(), ctx.format("color")) - formats.begin()));
    pointLightCount_ = gl::Uniform(shade_, "u_pointLightCount");
    ambientAndSun_ = gl::Uniform(shade_, "u_ambientAndSun");
    load_ = gl::Uniform(shade_, "u_load");
    if (buffer_) glDeleteBuffers(1, &buffer_);
    if (farFields_) glDeleteBuffers(1, &farFields_);
    buffer_ = farFields_ = 0;
    if (ctx.bound(clusters::kSlot)) return;  // another pass builds the lists (the check refuses far_field then)
    const clusters::Grid g = clusters::grid(ctx.params());
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, static_cast<GLsizeiptr>(clusters::bufferBytes(g, ctx.extent("color"))), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    // After the shading programs: the bins', then the far field's.
    const Extent size = ctx.extent("color");
    bins_.setup(ctx.program(1 + formats.size()), binGrid(ctx.params()), size);
    if (!farField(ctx.params())) return;
    far_ = ctx.program(2 + formats.size());
    farLightCount_ = gl::Uniform(far_, "u_pointLightCount");
    tiles_ = {(size.width + g.tileSize - 1) / g.tileSize, (size.height + g.tileSize - 1) / g.tileSize};
    glCreateBuffers(1, &farFields_);
    glNamedBufferStorage(farFields_, static_cast<GLsizeiptr>(tiles_.width) * tiles_.height * g.slices * kFarFieldRecord * 4,
                         nullptr, 0);
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const Extent size = ctx.extent("color");
    const int lights = ctx.params().getBool("point_lights") ? static_cast<int>(scene.pointLightCount()) : 0;
    lighting::bindPointLights(scene, lighting::threshold(ctx.params()));
    shadows::bindInfo(ctx, shade_);
    ibl::setUniforms(ctx, shade_);
    if (buffer_) {
      bins_.build(lights, size);  // what the list build (and the far field) culls
      builder_.build(scene, buffer_, clusters::grid(ctx.params()), size, lights, lighting::threshold(ctx.params()),
                     /*barrier=*/true);
    } else {
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, clusters::kBinding, ctx.buffer(clusters::kSlot));
    }
    if (farFields_) {
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFarFieldBinding, farFields_);
      glUseProgram(far_);
      farLightCount_.set(lights);
      glDispatchCompute(tiles_.width, tiles_.height, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glUseProgram(shade_);
    pointLightCount_.set(lights);
    ambientAndSun_.set(ctx.params().getBool("ambient_and_sun"));
    load_.set(ctx.loads("color"));
    glBindImageTexture(0, ctx.texture("color"), 0, GL_FALSE, 0, GL_READ_WRITE,
                       lighting::hdrImageFormat(ctx.format("color")));
    glDispatchCompute((size.width + kShadeGroup - 1) / kShadeGroup, (size.height + kShadeGroup - 1) / kShadeGroup, 1);
    // No barrier for the target: the executor issues what its next user needs
    // (storage_write slot). The cluster buffer stays bound on binding 1 until
    // the next pass that uses it, so a test can read its overflow counter.
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
  }

 private:
  uint32_t shade_ = 0, buffer_ = 0, far_ = 0, farFields_ = 0;
  Extent tiles_;
  clusters::Builder builder_;
  lighting::LightBins bins_;
  gl::Uniform pointLightCount_, ambientAndSun_, load_, farLightCount_;
};

PassTypeDesc makeClusteredDeferredPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::computeLightingPass(
      "clustered_deferred",
      "Clustered deferred lighting (compute): point lights culled per view-space cluster (screen tile x "
      "exponential depth slice) into lists, each pixel shaded with its cluster's list");
  d.slots.push_back(clusters::readerSlot(
      "light lists a cluster_lights pass built (its grid and cut-off apply; this pass's grid parameters do not); "
      "unbound: the pass builds its own"));
  // 16-pixel tiles: lists bounded by their pixels' depths are then ~2.7x what
  // reaches a pixel at 1,024 lights in the many-lights scene (4.2x at 32).
  for (auto& p : clusters::gridParams(16)) d.params.push_back(std::move(p));
  d.params.push_back(param("overflow", ParamType::enumeration, std::string("shade_all"),
                           "a cluster with more lights than its list holds: shade_all (every light there; correct, "
                           "slow) or truncate (only the listed ones; wrong, shows where clusters overflow)",
                           {"shade_all", "truncate"}));
  d.params.push_back(lighting::farFieldParam());
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  shadows::declareReader(d);
  ibl::declareReader(d);
  d.programs = [](const ParamSet& p) {
    std::vector<ShaderProgramSpec> v;
    v.push_back(clusters::depthBoundedBuildProgram(p, lighting::binDefines(binGrid(p))));
    for (Format target : hdrFormats()) {  // setup() takes the one of the bound target's format
      ShaderProgramSpec s;
      s.comp = "clustered_deferred.comp";
      s.defines = shadingDefines(p);
      s.defines.push_back(std::string("TARGET_FORMAT=") + lighting::hdrImageQualifier(target));
      if (p.getString("overflow") == "truncate") s.defines.push_back("CLUSTER_OVERFLOW_TRUNCATE");
      s.samplers = lighting::gbufferSamplers();
      s.drawsToAttachments = false;
      shadows::addToProgram(s, p);
      ibl::addToProgram(s, p);
      v.push_back(std::move(s));
    }
    std::vector<std::string> defines = shadingDefines(p);
    for (auto& g : clusters::gridDefines(p)) defines.push_back(std::move(g));
    v.push_back(lighting::binProgram(defines, binGrid(p)));
    if (farField(p)) {
      ShaderProgramSpec far;
      far.comp = "clustered_far.comp";
      far.defines = std::move(defines);
      for (auto& b : lighting::binDefines(binGrid(p))) far.defines.push_back(std::move(b));
      far.samplers = lighting::gbufferSamplers();
      far.drawsToAttachments = false;
      v.push_back(std::move(far));
    }
    return v;
  };
  // The G-buffer's slots: gbufferReader's rule.
  d.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    clusters::checkReaderSlot(ctx, checks);
    if (farField(ctx.params()) && ctx.bound(clusters::kSlot))
      checks.slotError(clusters::kSlot, "far_field sums per cluster what the pass's own lists leave out: leave '" +
                                            std::string(clusters::kSlot) +
                                            "' unbound (the pass builds its lists) or set far_field false");
  };
  d.create = [] { return std::make_unique<ClusteredDeferredPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeClusteredDeferredPass);
}  // namespace
