// Which GL context is current on this thread, as its window system names it,
// for objects that belong to one context: the executor's framebuffers and
// vertex arrays, a scene's upload (rgraph/renderer.h). GL itself has no
// name for a context; EGL (headless, rgraph's own) and GLX (GLFW on X11, the
// viewer) do.
#pragma once


namespace rgraph::gl {

struct ContextIdentity {
  const void* egl = nullptr;  // eglGetCurrentContext()
  const void* glx = nullptr;  // glXGetCurrentContext(), when libGLX is loaded
  bool operator==(const ContextIdentity&) const = default;
};

// The context current now (both null: none, or one of a window system this
// does not know; callers then fall back to a cheaper test of their own).
ContextIdentity currentContext();

}  // namespace rgraph::gl
