// The GPU-deformed vertices of a scene read back: scene.vert itself (the
// source every scene pass compiles, with SCENE_ANIMATION) plus its
// CAPTURE_VERTICES lines, which write each vertex's world position and clip
// positions (now, previous frame) into a storage buffer, drawn by GpuScene as
// every pass draws it, rasterizer off. (Transform feedback cannot be used:
// GpuScene binds the program itself, which GL refuses while feedback is active.)
#pragma once

#include <GL/glcorearb.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/scene.h"

namespace deformtest {

using namespace rgraph;

inline std::string asset(const std::string& rel) {
  std::string path = RGRAPH_ASSETS_DIR;
  path += "/gltf/";
  path += rel;
  return path;
}

// Per primitive, per vertex of its mesh (those its indices draw; zeros elsewhere).
struct Captured {
  std::vector<std::vector<glm::vec4>> world, clipNow, clipPrev;
};

class DeformCapture {
 public:
  // animation: SCENE_ANIMATION (off: what a static scene's shaders draw).
  explicit DeformCapture(ShaderLibrary& shaders, bool animation = true) {
    std::vector<std::string> defines = {"CAPTURE_VERTICES"};
    if (animation) defines.push_back("SCENE_ANIMATION");
    program_ = shaders.program("scene.vert", "capture_discard.frag", defines);
  }
  uint32_t program() const { return program_; }

  Captured capture(GpuScene& gpu) const {
    const Scene& s = gpu.scene();
    size_t stride = 1;
    for (const MeshData& m : s.meshes) stride = std::max(stride, m.vertexCount());
    const size_t entries = 3 * stride * std::max<size_t>(s.primitives.size(), 1);
    gl::Buffer buffer = gl::createBuffer();
    std::vector<glm::vec4> data(entries, glm::vec4(0.0f));
    glNamedBufferStorage(buffer.id(), GLsizeiptr(entries * sizeof(glm::vec4)), data.data(), GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, buffer.id());
    glProgramUniform1i(program_, glGetUniformLocation(program_, "u_captureStride"), GLint(stride));
    // A complete framebuffer to draw into (a headless context has none by default).
    gl::Texture color = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(color.id(), 1, GL_RGBA8, 1, 1);
    gl::Framebuffer fbo = gl::createFramebuffer();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glEnable(GL_RASTERIZER_DISCARD);
    GpuScene::DrawOptions o;
    o.filter = GpuScene::Filter::all;
    o.cullBackFaces = false;
    gpu.drawPrimitives(program_, o);
    glDisable(GL_RASTERIZER_DISCARD);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(entries * sizeof(glm::vec4)), data.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, 0);
    Captured c;
    for (size_t i = 0; i < s.primitives.size(); ++i) {
      const size_t n = s.meshes[size_t(s.primitives[i].mesh)].vertexCount();
      c.world.emplace_back();
      c.clipNow.emplace_back();
      c.clipPrev.emplace_back();
      for (size_t v = 0; v < n; ++v) {
        const size_t at = 3 * (i * stride + v);
        c.world.back().push_back(data[at]);
        c.clipNow.back().push_back(data[at + 1]);
        c.clipPrev.back().push_back(data[at + 2]);
      }
    }
    return c;
  }

 private:
  uint32_t program_ = 0;
};

// The vertices a primitive's indices draw (the captured ones).
inline std::vector<uint32_t> drawnVertices(const MeshData& m) {
  std::vector<uint32_t> v = m.indices;
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace deformtest
