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

namespace {
// One object named by a glCreate* call (`create(args..., 1, &id)`).
template <typename Object, typename Create, typename... Args>
Object createOne(Create create, Args... args) {
  GLuint id = 0;
  create(args..., 1, &id);
  return Object(id);
}
}  // namespace

Texture createTexture(unsigned target) { return createOne<Texture>(glCreateTextures, target); }
Framebuffer createFramebuffer() { return createOne<Framebuffer>(glCreateFramebuffers); }
Buffer createBuffer() { return createOne<Buffer>(glCreateBuffers); }
Program createProgram() { return Program(glCreateProgram()); }
Shader createShader(unsigned stage) { return Shader(glCreateShader(stage)); }
VertexArray createVertexArray() { return createOne<VertexArray>(glCreateVertexArrays); }
Query createQuery(unsigned target) { return createOne<Query>(glCreateQueries, target); }
Sampler createSampler() { return createOne<Sampler>(glCreateSamplers); }

}  // namespace rgraph::gl
