#include "rgraph/gl/objects.h"

#include <GL/glcorearb.h>

#include <array>
#include <atomic>

namespace rgraph::gl {
namespace {
std::array<std::atomic<int64_t>, static_cast<size_t>(ObjectKind::count_)> gLive{};
std::array<std::atomic<int64_t>, static_cast<size_t>(ObjectKind::count_)> gCreated{};
}

const char* objectKindName(ObjectKind k) {
  switch (k) {
    case ObjectKind::texture: return "texture";
    case ObjectKind::framebuffer: return "framebuffer";
    case ObjectKind::buffer: return "buffer";
    case ObjectKind::program: return "program";
    case ObjectKind::shader: return "shader";
    case ObjectKind::vertex_array: return "vertex_array";
    case ObjectKind::query: return "query";
    case ObjectKind::sampler: return "sampler";
    case ObjectKind::count_: break;
  }
  return "unknown";
}

int64_t liveObjects(ObjectKind k) { return gLive[static_cast<size_t>(k)].load(); }

int64_t createdObjects(ObjectKind k) { return gCreated[static_cast<size_t>(k)].load(); }

int64_t createdObjectsTotal() {
  int64_t n = 0;
  for (const auto& c : gCreated) n += c.load();
  return n;
}

int64_t liveObjectsTotal() {
  int64_t n = 0;
  for (const auto& c : gLive) n += c.load();
  return n;
}

namespace detail {
void countCreated(ObjectKind k) {
  gLive[static_cast<size_t>(k)].fetch_add(1);
  gCreated[static_cast<size_t>(k)].fetch_add(1);
}

void destroy(ObjectKind k, uint32_t id) {
  switch (k) {
    case ObjectKind::texture: glDeleteTextures(1, &id); break;
    case ObjectKind::framebuffer: glDeleteFramebuffers(1, &id); break;
    case ObjectKind::buffer: glDeleteBuffers(1, &id); break;
    case ObjectKind::program: glDeleteProgram(id); break;
    case ObjectKind::shader: glDeleteShader(id); break;
    case ObjectKind::vertex_array: glDeleteVertexArrays(1, &id); break;
    case ObjectKind::query: glDeleteQueries(1, &id); break;
    case ObjectKind::sampler: glDeleteSamplers(1, &id); break;
    case ObjectKind::count_: return;
  }
  gLive[static_cast<size_t>(k)].fetch_sub(1);
}
}  // namespace detail

Texture createTexture(unsigned target) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  return Texture(id);
}
Framebuffer createFramebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return Framebuffer(id);
}
Buffer createBuffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return Buffer(id);
}
Program createProgram() { return Program(glCreateProgram()); }
Shader createShader(unsigned stage) { return Shader(glCreateShader(stage)); }
VertexArray createVertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArray(id);
}
Query createQuery(unsigned target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return Query(id);
}
Sampler createSampler() {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  return Sampler(id);
}

}  // namespace rgraph::gl
