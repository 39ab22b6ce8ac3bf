#include "gl_wait_log.h"

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <EGL/egl.h>
#include <GL/glcorearb.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <set>

namespace rgraph::stalltest {
namespace {

GlWaits& log() {
  static GlWaits w;
  return w;
}
// Queries whose GL_QUERY_RESULT_AVAILABLE was seen true since their last glBeginQuery.
std::set<GLuint>& seenAvailable() {
  static std::set<GLuint> s;
  return s;
}

// libOpenGL's function of that name (the next definition after this program's).
template <typename Fn>
Fn real(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);
  if (!f) f = reinterpret_cast<void*>(eglGetProcAddress(name));
  if (!f) {
    std::fprintf(stderr, "gl_wait_log: %s not found\n", name);
    std::abort();
  }
  return reinterpret_cast<Fn>(f);
}

void blocked(const char* name) { ++log().blocking[name]; }
// A read-back into a pixel pack buffer queues a copy on the GPU: it waits
// only for a client-memory destination.
void readBack(const char* name) {
  GLint packBuffer = 0;
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
  if (packBuffer == 0) blocked(name);
  else ++log().packBufferReads;
}

void resultRead(GLuint id, GLenum pname, const char* getter) {
  if (pname != GL_QUERY_RESULT) return;
  ++log().resultReads;
  if (!seenAvailable().count(id))
    log().unavailableReads.push_back(std::string(getter) + "(" + std::to_string(id) +
                                     ", GL_QUERY_RESULT) before GL_QUERY_RESULT_AVAILABLE was seen true");
}

void availability(GLuint id, GLenum pname, bool in) {
  if (pname != GL_QUERY_RESULT_AVAILABLE) return;
  ++log().availabilityChecks;
  if (in) seenAvailable().insert(id);
}

}  // namespace

void resetWaits() { log() = GlWaits{}; }
GlWaits waits() { return log(); }

}  // namespace rgraph::stalltest

using rgraph::stalltest::availability;
using rgraph::stalltest::blocked;
using rgraph::stalltest::readBack;
using rgraph::stalltest::real;
using rgraph::stalltest::resultRead;

// The entry points, under their own names. Each static `fn` is looked up once.
#define RGRAPH_FORWARD(ret, name, params, args, record)                        \
  extern "C" __attribute__((visibility("default"))) ret APIENTRY name params { \
    static const auto fn = real<ret(APIENTRY*) params>(#name);                 \
    record;                                                                    \
    return fn args;                                                            \
  }

RGRAPH_FORWARD(void, glFinish, (void), (), blocked("glFinish"))
RGRAPH_FORWARD(void, glReadPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void* p),
               (x, y, w, h, f, t, p), readBack("glReadPixels"))
RGRAPH_FORWARD(void, glReadnPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, GLsizei n, void* p),
               (x, y, w, h, f, t, n, p), readBack("glReadnPixels"))
RGRAPH_FORWARD(void, glGetTextureImage, (GLuint tex, GLint l, GLenum f, GLenum t, GLsizei n, void* p),
               (tex, l, f, t, n, p), readBack("glGetTextureImage"))
RGRAPH_FORWARD(void, glGetTexImage, (GLenum target, GLint l, GLenum f, GLenum t, void* p), (target, l, f, t, p),
               readBack("glGetTexImage"))
RGRAPH_FORWARD(void, glGetTextureSubImage,
               (GLuint tex, GLint l, GLint x, GLint y, GLint z, GLsizei w, GLsizei h, GLsizei d, GLenum f, GLenum t,
                GLsizei n, void* p),
               (tex, l, x, y, z, w, h, d, f, t, n, p), readBack("glGetTextureSubImage"))
RGRAPH_FORWARD(void, glGetNamedBufferSubData, (GLuint b, GLintptr o, GLsizeiptr s, void* p), (b, o, s, p),
               blocked("glGetNamedBufferSubData"))
RGRAPH_FORWARD(void, glGetBufferSubData, (GLenum target, GLintptr o, GLsizeiptr s, void* p), (target, o, s, p),
               blocked("glGetBufferSubData"))
RGRAPH_FORWARD(void*, glMapNamedBufferRange, (GLuint b, GLintptr o, GLsizeiptr s, GLbitfield a), (b, o, s, a),
               blocked("glMapNamedBufferRange"))
RGRAPH_FORWARD(void*, glMapBufferRange, (GLenum target, GLintptr o, GLsizeiptr s, GLbitfield a), (target, o, s, a),
               blocked("glMapBufferRange"))
RGRAPH_FORWARD(void*, glMapNamedBuffer, (GLuint b, GLenum a), (b, a), blocked("glMapNamedBuffer"))
RGRAPH_FORWARD(void*, glMapBuffer, (GLenum target, GLenum a), (target, a), blocked("glMapBuffer"))
RGRAPH_FORWARD(GLenum, glClientWaitSync, (GLsync s, GLbitfield f, GLuint64 t), (s, f, t), blocked("glClientWaitSync"))
RGRAPH_FORWARD(void, glBeginQuery, (GLenum target, GLuint id), (target, id),
               (rgraph::stalltest::seenAvailable().erase(id),
                target == GL_TIME_ELAPSED ? ++rgraph::stalltest::log().queriesBegun : 0))

// The four query getters: a result read is judged before the call; an
// availability answer is recorded after it.
#define RGRAPH_QUERY_GETTER(name, type)                                                                    \
  extern "C" __attribute__((visibility("default"))) void APIENTRY name(GLuint id, GLenum pname, type* v) { \
    static const auto fn = real<void(APIENTRY*)(GLuint, GLenum, type*)>(#name);                            \
    resultRead(id, pname, #name);                                                                          \
    fn(id, pname, v);                                                                                      \
    availability(id, pname, *v != 0);                                                                      \
  }
RGRAPH_QUERY_GETTER(glGetQueryObjectiv, GLint)
RGRAPH_QUERY_GETTER(glGetQueryObjectuiv, GLuint)
RGRAPH_QUERY_GETTER(glGetQueryObjecti64v, GLint64)
RGRAPH_QUERY_GETTER(glGetQueryObjectui64v, GLuint64)
