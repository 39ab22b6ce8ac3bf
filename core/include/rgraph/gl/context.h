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

// The device a context runs on: what `rgraph render --stats` and `rgraph
// bench` record, and what the context's creation logs (debug level).
struct ContextDevice {
  std::string platform;              // GlContext::platform()
  int eglDevice = -1;                // index in EGL's device enumeration (what RGRAPH_EGL_DEVICE names);
                                     // -1 when the context is not on the device platform
  std::string eglDeviceDescription;  // that device (rgraph/gl/egl_device.h): "software (EGL_MESA_device_software)",
                                     // "hardware, CUDA (EGL_NV_device_cuda), /dev/dri/renderD128, ..."; empty when -1
  std::string vendor;                // GL_VENDOR
  std::string renderer;              // GL_RENDERER
  std::string version;               // GL_VERSION
};
// One line: "RENDERER, OpenGL VERSION, VENDOR (PLATFORM[ N: DEVICE])".
std::string describeContext(const ContextDevice& device);

// Whether the current context lists the extension `name` (GL_NUM_EXTENSIONS,
// glGetStringi): for the features a 4.5 core context may lack (anisotropic
// filtering, gl_Layer from the vertex shader, memory queries).
bool hasExtension(const char* name);

class GlContext {
 public:
  // Throws rgraph::RuntimeError with the reason when no 4.5 core context can be made.
  // Headless: with $RGRAPH_EGL_DEVICE=N (0-based), EGL device N of
  // EGL_EXT_device_enumeration through EGL_EXT_platform_device, nothing else
  // (not a number, or no device N: the error lists the devices). Without it,
  // the first hardware device that gives a context (a GPU: any device
  // without EGL_MESA_device_software; NVIDIA's need no DRM node), then as
  // when none exists: EGL surfaceless (Mesa), the other devices (llvmpipe's),
  // eglGetDisplay(EGL_DEFAULT_DISPLAY). The variable is ignored for windows.
  static std::unique_ptr<GlContext> create(const ContextOptions& options = {});
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // GL_RENDERER, GL_VERSION and GL_VENDOR, read when the context was made
  // (the same whichever context is current now).
  std::string renderer() const;
  std::string version() const;
  std::string vendor() const;
  std::string platform() const;  // "egl-device", "egl-surfaceless", "egl-default" or "glfw"
  ContextDevice device() const;  // all of the above, and the EGL device
  bool isSoftware() const;       // llvmpipe / softpipe / swrast
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
