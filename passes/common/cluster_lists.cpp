#include "rgraph/passes/cluster_lists.h"

#include <GL/glcorearb.h>

#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/invocation_order.h"
#include "rgraph/passes/light_radii.h"
#include "rgraph/passes/lighting_options.h"

namespace rgraph::clusters {

std::vector<ParamDecl> gridParams(int defaultTileSize) {
  using namespace rgraph::decl;
  return {
      ranged("tile_size", ParamType::integer, int64_t{defaultTileSize}, 4, 256, "cluster width and height in pixels"),
      ranged("slices", ParamType::integer, int64_t{24}, 1, 256,
             "depth slices, spaced exponentially from the camera's near to its far plane"),
      ranged("max_cluster_lights", ParamType::integer, int64_t{256}, 1, 4096,
             "lights one cluster's list holds; a cluster reached by more keeps the true count, is counted in the "
             "list buffer's header, and its pixels shade every light (or, with clustered_deferred's overflow "
             "truncate, only the listed ones)"),
  };
}

Grid grid(const ParamSet& p) {
  return {static_cast<int>(p.getInt("tile_size")), static_cast<int>(p.getInt("slices")),
          static_cast<int>(p.getInt("max_cluster_lights"))};
}

uint64_t bufferBytes(const Grid& g, Extent size) {
  const uint64_t tiles = uint64_t{(size.width + g.tileSize - 1) / g.tileSize} * ((size.height + g.tileSize - 1) / g.tileSize);
  return (4 + tiles * g.slices * (1 + uint64_t(g.maxLights))) * 4;
}

std::vector<std::string> gridDefines(const ParamSet& p) {
  const Grid g = grid(p);
  return {"TILE_SIZE=" + std::to_string(g.tileSize), "SLICES=" + std::to_string(g.slices),
          "MAX_CLUSTER_LIGHTS=" + std::to_string(g.maxLights)};
}

ShaderProgramSpec buildProgram(const ParamSet& p) {
  ShaderProgramSpec build;
  build.comp = "clustered_build.comp";
  build.defines = gridDefines(p);
  invocations::addPermuteDefine(p, build.defines);
  build.drawsToAttachments = false;
  return build;
}

ShaderProgramSpec depthBoundedBuildProgram(const ParamSet& p, std::vector<std::string> binDefines) {
  ShaderProgramSpec build = buildProgram(p);
  for (auto& d : lighting::shadingDefines(p)) build.defines.push_back(std::move(d));
  for (auto& d : binDefines) build.defines.push_back(std::move(d));
  build.defines.push_back("CLUSTER_DEPTH_BOUNDS");
  build.samplers = lighting::gbufferSamplers();
  build.drawsToAttachments = false;
  return build;
}

SlotDecl readerSlot(std::string description) {
  return decl::slot(kSlot, Access::storage_read, false, SlotDecl::Load::never, std::move(description));
}

void checkReaderSlot(const PassCheckContext& ctx, PassChecks& checks) {
  const CheckedSlot* s = ctx.find(kSlot);
  if (s && s->format)
    checks.slotError(kSlot, "'" + s->resource +
                                "' is a texture; bind the buffer a cluster_lights pass writes its light lists into");
}

void checkBuilderSlot(const PassCheckContext& ctx, PassChecks& checks, const std::string& slot) {
  const CheckedSlot* s = ctx.find(slot);
  if (!s) return;
  if (s->format) {
    checks.slotError(slot, "'" + s->resource + "' is a texture; the light lists go into a buffer (\"type\": \"buffer\")");
    return;
  }
  const Grid g = grid(ctx.params());
  const uint64_t need = bufferBytes(g, ctx.outputExtent());
  if (s->kind == ResourceKind::buffer && s->bufferBytes < need)
    checks.slotError(slot, "buffer '" + s->resource + "' holds " + std::to_string(s->bufferBytes) + " bytes; the lists of a " +
                               extentText(ctx.outputExtent()) + " output at tile_size " + std::to_string(g.tileSize) +
                               ", " + std::to_string(g.slices) + " slices and max_cluster_lights " +
                               std::to_string(g.maxLights) + " need " + std::to_string(need) +
                               " (raise its buffer_bytes, or the tile size, or lower max_cluster_lights)");
}

Builder::Builder(uint32_t program) : program_(program), lightCount_(program, "u_pointLightCount") {}

void Builder::build(GpuScene& scene, uint32_t buffer, const Grid& g, Extent size, int lights, float threshold,
                    bool barrier) const {
  const GLuint header[4] = {0, static_cast<GLuint>(g.tileSize), static_cast<GLuint>(g.slices),
                            static_cast<GLuint>(g.maxLights)};
  glNamedBufferSubData(buffer, 0, sizeof header, header);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, buffer);
  if (lights <= 0) return;
  lighting::bindPointLights(scene, threshold);
  glUseProgram(program_);
  lightCount_.set(lights);
  glDispatchCompute((size.width + g.tileSize - 1) / g.tileSize, (size.height + g.tileSize - 1) / g.tileSize, 1);
  if (barrier) glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace rgraph::clusters
