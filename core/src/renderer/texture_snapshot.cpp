#include "texture_snapshot.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "rgraph/gl/gl_state.h"

namespace rgraph::hazard_detail {

namespace {

// shaders/hazard_samples.comp's defines for a texture of this kind.
std::vector<std::string> fetchDefines(int kind, bool arrayed) {
  std::vector<std::string> d;
  if (arrayed) d.push_back("ARRAYED");
  if (kind == 1) d.push_back("INT_TEXELS");
  if (kind == 2) d.push_back("UINT_TEXELS");
  return d;
}

}  // namespace

Snapshot SnapshotReader::read(uint32_t texture, bool depth) {
  Snapshot s;
  GLint target = 0, levels = 0;
  glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
  if (target == GL_TEXTURE_2D_MULTISAMPLE || target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY)
    return readMultisampled(texture, static_cast<unsigned>(target));
  glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  for (GLint l = 0; l < std::max(levels, 1); ++l) {
    GLint w = 0, h = 0, d = 1;
    glGetTextureLevelParameteriv(texture, l, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(texture, l, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(texture, l, GL_TEXTURE_DEPTH, &d);
    Level level;
    level.width = static_cast<uint32_t>(w), level.height = static_cast<uint32_t>(h);
    level.layers = target == GL_TEXTURE_CUBE_MAP ? 6u : static_cast<uint32_t>(std::max(d, 1));
    level.channels = depth ? 1 : 4;
    level.texels.resize(size_t{level.width} * level.height * level.layers * level.channels);
    const auto bytes = static_cast<GLsizei>(level.texels.size() * sizeof(float));
    GLint type = 0;
    glGetTextureLevelParameteriv(texture, l, GL_TEXTURE_RED_TYPE, &type);
    level.integer = !depth && (type == GL_INT || type == GL_UNSIGNED_INT);
    if (level.integer) {  // the bits, compared as such (the harness compares bits first)
      std::vector<uint32_t> ids(level.texels.size());
      glGetTextureImage(texture, l, GL_RGBA_INTEGER, GL_UNSIGNED_INT, bytes, ids.data());
      if (!ids.empty()) std::memcpy(level.texels.data(), ids.data(), ids.size() * sizeof(uint32_t));
    } else {
      glGetTextureImage(texture, l, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, bytes, level.texels.data());
    }
    s.push_back(std::move(level));
  }
  return s;
}

// Depth textures read through the float sampler: texelFetch gives (depth, 0, 0, 1).
Snapshot SnapshotReader::readMultisampled(uint32_t texture, unsigned target) {
  const bool arrayed = target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
  GLint w = 0, h = 0, d = 1, samples = 1, type = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &h);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH, &d);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_SAMPLES, &samples);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_TYPE, &type);
  const int kind = type == GL_INT ? 1 : type == GL_UNSIGNED_INT ? 2 : 0;
  Level level;
  level.width = static_cast<uint32_t>(std::max(w, 0)), level.height = static_cast<uint32_t>(std::max(h, 0));
  level.layers = arrayed ? static_cast<uint32_t>(std::max(d, 1)) : 1u;
  level.samples = static_cast<uint32_t>(std::max(samples, 1));
  level.channels = 4 * level.samples;
  level.integer = kind != 0;
  level.texels.resize(size_t{level.width} * level.height * level.layers * level.channels);
  if (level.texels.empty()) return {level};
  const size_t bytes = level.texels.size() * sizeof(uint32_t);
  if (wordCapacity_ < bytes) {
    words_ = gl::createBuffer();
    glNamedBufferStorage(words_.id(), static_cast<GLsizeiptr>(bytes), nullptr, 0);
    wordCapacity_ = bytes;
  }
  const uint32_t program = shaders_.computeProgram("hazard_samples.comp", fetchDefines(kind, arrayed));
  {
    gl::GlStateGuard guard;  // the next pass finds the units, buffers and program the frame left
    glUseProgram(program);
    glProgramUniform1i(program, glGetUniformLocation(program, "u_samples"), samples);
    glBindTextureUnit(0, texture);
    glBindSampler(0, 0);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, words_.id(), 0, static_cast<GLsizeiptr>(bytes));
    glDispatchCompute((level.width + 7) / 8, (level.height + 7) / 8, level.layers);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  glGetNamedBufferSubData(words_.id(), 0, static_cast<GLsizeiptr>(bytes), level.texels.data());
  return {level};
}

}  // namespace rgraph::hazard_detail
