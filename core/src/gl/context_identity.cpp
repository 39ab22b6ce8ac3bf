#include "rgraph/gl/context_identity.h"

#include <EGL/egl.h>
#include <dlfcn.h>

#include <atomic>

namespace rgraph::gl {
namespace {

using GetCurrentContext = const void* (*)();

// glXGetCurrentContext without linking libGLX: a GLX context can be current
// only when a library that provides GLX is already loaded (GLFW dlopens it),
// so look it up among the loaded ones (RTLD_NOLOAD) and never load one.
GetCurrentContext glxGetCurrentContext() {
  static std::atomic<GetCurrentContext> cached{nullptr};  // kept once found; looked up again until then
  if (GetCurrentContext f = cached.load()) return f;
  GetCurrentContext found = nullptr;
  for (const char* library : {"libGLX.so.0", "libGL.so.1"}) {
    void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD);
    if (!handle) continue;
    found = reinterpret_cast<GetCurrentContext>(dlsym(handle, "glXGetCurrentContext"));
    dlclose(handle);  // still loaded: its loader holds it
    if (found) break;
  }
  if (found) cached.store(found);
  return found;
}

}  // namespace

ContextIdentity currentContext() {
  ContextIdentity id;
  id.egl = eglGetCurrentContext();
  if (GetCurrentContext glx = glxGetCurrentContext()) id.glx = glx();
  return id;
}

}  // namespace rgraph::gl
