// clustered_deferred: deferred lighting over view-space clusters, in two
// compute dispatches. The first builds, per cluster (a screen tile times an
// exponential depth slice, shaders/include/clusters.glsl), the list of point
// lights whose sphere touches the cluster's box, into a storage buffer the
// pass owns (a work group per tile: the lights are culled against the tile's
// side planes first, then each slice tests only those). The second shades
// every pixel with its cluster's list and stores the HDR result. Unlike
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

#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/uniform.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

// The storage buffer binding of the cluster lists (the lights are on 0).
constexpr GLuint kClusterBinding = 1;
constexpr int kShadeGroup = 8;  // clustered_deferred.comp's local_size_x and _y

std::vector<std::string> gridDefines(const ParamSet& p) {
  return {"TILE_SIZE=" + std::to_string(p.getInt("tile_size", 32)), "SLICES=" + std::to_string(p.getInt("slices", 24)),
          "MAX_CLUSTER_LIGHTS=" + std::to_string(p.getInt("max_cluster_lights", 256))};
}

class ClusteredDeferredPass final : public PassInstance {
 public:
  ~ClusteredDeferredPass() override {
    if (buffer_) glDeleteBuffers(1, &buffer_);
  }

  void setup(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    tile_ = static_cast<int>(p.getInt("tile_size", 32));
    slices_ = static_cast<int>(p.getInt("slices", 24));
    maxLights_ = static_cast<int>(p.getInt("max_cluster_lights", 256));
    // programs(): the build program, then one shading program per target
    // format in the order of hdrFormats() (the image format is a define).
    build_ = ctx.program(0);
    buildLightCount_ = gl::Uniform(build_, "u_pointLightCount");
    const auto& formats = lighting::hdrFormats();
    shade_ = ctx.program(1 + (std::find(formats.begin(), formats.end(), ctx.format("color")) - formats.begin()));
    pointLightCount_ = gl::Uniform(shade_, "u_pointLightCount");
    ambientAndSun_ = gl::Uniform(shade_, "u_ambientAndSun");
    load_ = gl::Uniform(shade_, "u_load");
    // Header (4 uints), one count per cluster, max_cluster_lights indices per cluster.
    const Extent size = ctx.extent("color");
    clusters_ =
        static_cast<GLsizeiptr>((size.width + tile_ - 1) / tile_) * ((size.height + tile_ - 1) / tile_) * slices_;
    const GLsizeiptr bytes = (4 + clusters_ * (1 + static_cast<GLsizeiptr>(maxLights_))) * 4;
    if (buffer_) glDeleteBuffers(1, &buffer_);
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  }

  void execute(PassContext& ctx) override {
    GpuScene& scene = *ctx.gpuScene();
    const Extent size = ctx.extent("color");
    const int lights = ctx.params().getBool("point_lights", true) ? static_cast<int>(scene.pointLightCount()) : 0;
    scene.bindFrame();
    scene.bindPointLights(lighting::threshold(ctx.params()));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kClusterBinding, buffer_);
    if (lights > 0) {
      const GLuint zero = 0;  // the header's overflow counter
      glNamedBufferSubData(buffer_, 0, sizeof(zero), &zero);
      glUseProgram(build_);
      buildLightCount_.set(lights);
      glDispatchCompute((size.width + tile_ - 1) / tile_, (size.height + tile_ - 1) / tile_, 1);  // a group per tile
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glUseProgram(shade_);
    pointLightCount_.set(lights);
    ambientAndSun_.set(ctx.params().getBool("ambient_and_sun", true));
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
  uint32_t build_ = 0, shade_ = 0, buffer_ = 0;
  int tile_ = 32, slices_ = 24, maxLights_ = 256;
  GLsizeiptr clusters_ = 0;
  gl::Uniform buildLightCount_, pointLightCount_, ambientAndSun_, load_;
};

PassTypeDesc makeClusteredDeferredPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = lighting::computeLightingPass(
      "clustered_deferred",
      "Clustered deferred lighting (compute): point lights culled per view-space cluster (screen tile x "
      "exponential depth slice) into lists, each pixel shaded with its cluster's list");
  d.params.push_back(
      ranged("tile_size", ParamType::integer, int64_t{32}, 4, 256, "cluster width and height in pixels"));
  d.params.push_back(ranged("slices", ParamType::integer, int64_t{24}, 1, 256,
                            "depth slices, spaced exponentially from the camera's near to its far plane"));
  d.params.push_back(ranged("max_cluster_lights", ParamType::integer, int64_t{256}, 1, 4096,
                            "lights one cluster's list holds; a cluster with more is counted in the list buffer's "
                            "header and handled as `overflow` says"));
  d.params.push_back(param("overflow", ParamType::enumeration, std::string("shade_all"),
                           "a cluster with more lights than its list holds: shade_all (every light there; correct, "
                           "slow) or truncate (only the listed ones; wrong, shows where clusters overflow)",
                           {"shade_all", "truncate"}));
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.programs = [](const ParamSet& p) {
    std::vector<ShaderProgramSpec> v;
    ShaderProgramSpec build;
    build.comp = "clustered_build.comp";
    build.defines = gridDefines(p);
    build.drawsToAttachments = false;
    v.push_back(std::move(build));
    for (Format target : lighting::hdrFormats()) {  // setup() takes the one of the bound target's format
      ShaderProgramSpec s;
      s.comp = "clustered_deferred.comp";
      s.defines = lighting::shadingDefines(p);
      for (auto& g : gridDefines(p)) s.defines.push_back(std::move(g));
      s.defines.push_back(std::string("TARGET_FORMAT=") + lighting::hdrImageQualifier(target));
      if (p.getString("overflow", "shade_all") == "truncate") s.defines.push_back("CLUSTER_OVERFLOW_TRUNCATE");
      s.samplers = lighting::gbufferSamplers();
      s.drawsToAttachments = false;
      v.push_back(std::move(s));
    }
    return v;
  };
  d.create = [] { return std::make_unique<ClusteredDeferredPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeClusteredDeferredPass);
}  // namespace
