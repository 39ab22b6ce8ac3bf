#include "rgraph/passes/light_bins.h"
#include "rgraph/passes/lighting_options.h"

#include <GL/glcorearb.h>

namespace rgraph::lighting {

namespace {
constexpr int kMaxBinLights = 512;
constexpr int kBinHeader = 200;  // include/tile_bins.glsl's BIN_HEADER
}  // namespace

std::vector<std::string> binDefines(const BinGrid& g) {
  return {"BIN_TILES=" + std::to_string(g.binTiles), "MAX_BIN_LIGHTS=" + std::to_string(kMaxBinLights),
          // With the far field the bins keep the lights within twice their
          // radius, so that the tiles or clusters, not the coarse bins, sum
          // the nearer unlisted ones.
          std::string("BIN_REACH=") + (g.farField ? "2.0" : "1.0"), "BIN_BINDING=" + std::to_string(g.binding)};
}

ShaderProgramSpec binProgram(std::vector<std::string> defines, const BinGrid& g) {
  ShaderProgramSpec bin;
  bin.comp = "tiled_bin.comp";
  for (auto& d : binDefines(g)) defines.push_back(std::move(d));
  bin.defines = std::move(defines);
  bin.samplers = gbufferSamplers();
  bin.drawsToAttachments = false;
  return bin;
}

LightBins::~LightBins() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

void LightBins::setup(uint32_t program, const BinGrid& g, Extent size) {
  program_ = program;
  grid_ = g;
  lightCount_ = gl::Uniform(program, "u_pointLightCount");
  const int px = g.binPixels();
  const GLsizeiptr bins =
      static_cast<GLsizeiptr>((size.width + px - 1) / px) * ((size.height + px - 1) / px);
  if (buffer_) glDeleteBuffers(1, &buffer_);
  glCreateBuffers(1, &buffer_);
  glNamedBufferStorage(buffer_, bins * (kBinHeader + kMaxBinLights) * 4, nullptr, 0);
}

void LightBins::build(int lights, Extent size) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, grid_.binding, buffer_);
  if (lights <= 0) return;
  const int px = grid_.binPixels();
  glUseProgram(program_);
  lightCount_.set(lights);
  glDispatchCompute((size.width + px - 1) / px, (size.height + px - 1) / px, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace rgraph::lighting
