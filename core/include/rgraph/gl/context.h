// An OpenGL 4.5 core context: headless (EGL, no surface; render into FBOs)
// or a GLFW window. The context is made current on the calling thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "rgraph/graph.h"

namespace rgraph {

struct ContextOptions {
  bool window = false;        // false: headless EGL; true: a GLFW window (needs a display)
  uint32_t width = 256, height = 256;  // window size (ignored headless)
  bool debug = true;          // debug context + KHR_debug callback into spdlog
  std::string title = "rgraph";
};

class GlContext {
 public:
  // Throws rgraph::RuntimeError with the reason when no 4.5 core context can be made.
  // Headless tries, in order: EGL surfaceless (Mesa), EGL device platform (NVIDIA),
  // eglGetDisplay(EGL_DEFAULT_DISPLAY).
  static std::unique_ptr<GlContext> create(const ContextOptions& options = {});
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  std::string renderer() const;   // GL_RENDERER
  std::string version() const;    // GL_VERSION
  std::string vendor() const;     // GL_VENDOR
  std::string platform() const;   // "egl-surfaceless", "egl-device", "egl-default" or "glfw"
  bool isSoftware() const;        // llvmpipe / softpipe / swrast
  bool hasWindow() const;

  // Window only (no-ops / false / {0,0} headless).
  void swapBuffers();
  bool shouldClose();
  void pollEvents();
  Extent windowFramebufferSize() const;

  // Make this context current on the calling thread again (releasing the one
  // current before, which may be of the other kind: EGL vs GLFW).
  void makeCurrent();
  // Leave no context current on this thread (if this one was).
  void releaseCurrent();

  // GL errors (GL_DEBUG_TYPE_ERROR, shader-compiler messages excluded: those
  // surface as RuntimeError from the ShaderLibrary) reported through KHR_debug
  // since creation. Stays 0 when debug is off.
  uint64_t debugErrorCount() const { return debugErrors_.load(); }
  // All debug messages received (any type/severity).
  uint64_t debugMessageCount() const { return debugMessages_.load(); }
  // The last error message reported (empty when none).
  std::string lastDebugError() const;

  struct Impl;

 private:
  GlContext();
  static std::unique_ptr<GlContext> createImpl(const ContextOptions& options);
  void installDebugCallback();
  friend struct DebugCallbackAccess;

  std::unique_ptr<Impl> impl_;
  std::atomic<uint64_t> debugErrors_{0};
  std::atomic<uint64_t> debugMessages_{0};
};

}  // namespace rgraph
