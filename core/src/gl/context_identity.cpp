#include "rgraph/gl/context_identity.h"

#include <EGL/egl.h>
#include <dlfcn.h>
#include <link.h>

#include <cstddef>

#include <atomic>

namespace rgraph::gl {
namespace {

using GetCurrentContext = const void* (*)();

// glXGetCurrentContext without linking libGLX: a GLX context can be current
// only when a library that provides GLX is already loaded (GLFW dlopens it),
// so look it up among the loaded ones (RTLD_NOLOAD) and never load one.
// dlopen, even RTLD_NOLOAD, searches the library path (tens of microseconds,
// asked at every frame): a miss is looked up again only once the loader has
// loaded something since (dl_iterate_phdr's load counter), a hit is kept.
unsigned long long loadsSoFar() {
  unsigned long long adds = 0;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t size, void* out) -> int {
        if (size >= offsetof(dl_phdr_info, dlpi_adds) + sizeof info->dlpi_adds)
          *static_cast<unsigned long long*>(out) = info->dlpi_adds;
        return 1;  // the counter is the same in every entry: the first will do
      },
      &adds);
  return adds;
}

GetCurrentContext glxGetCurrentContext() {
  static std::atomic<GetCurrentContext> cached{nullptr};  // kept once found
  static std::atomic<unsigned long long> missedAt{~0ull};  // loads counted at the last miss
  if (GetCurrentContext f = cached.load()) return f;
  const unsigned long long loads = loadsSoFar();
  if (loads != 0 && loads == missedAt.load()) return nullptr;  // nothing loaded since
  GetCurrentContext found = nullptr;
  for (const char* library : {"libGLX.so.0", "libGL.so.1"}) {
    void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD);
    if (!handle) continue;
    found = reinterpret_cast<GetCurrentContext>(dlsym(handle, "glXGetCurrentContext"));
    dlclose(handle);  // still loaded: its loader holds it
    if (found) break;
  }
  if (found)
    cached.store(found);
  else
    missedAt.store(loads);
  return found;
}

}  // namespace

ContextIdentity currentContext() {
  ContextIdentity id;
  id.egl = eglGetCurrentContext();
  // One thread has at most one current context across EGL and GLX (libglvnd
  // refuses to make one current while the other is): with an EGL context
  // current there is no GLX one to ask about.
  if (id.egl) return id;
  if (GetCurrentContext glx = glxGetCurrentContext()) id.glx = glx();
  return id;
}

}  // namespace rgraph::gl
