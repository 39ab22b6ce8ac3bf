#include "rgraph/gl/context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <malloc.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/gl/egl_device.h"

namespace rgraph {

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLFWwindow* window = nullptr;
  std::string platform;
  int eglDevice = -1;
  std::string eglDeviceDescription;
  std::string vendor, renderer, version;  // read once, when the context was made
  mutable std::mutex mutex;
  std::string lastError;
};

namespace {

std::string eglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04x", e);
      return buf;
    }
  }
}

using gl::hasEglExtension;

std::string glString(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : std::string();
}

void tuneMalloc() {
  static std::once_flag once;
  std::call_once(once, [] {
    // llvmpipe is 2-3.5x slower when glibc keeps returning freed heap to the OS.
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
  });
}

const char* debugSourceName(GLenum s) {
  switch (s) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window-system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader-compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third-party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
  }
}

const char* debugTypeName(GLenum t) {
  switch (t) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined-behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    case GL_DEBUG_TYPE_MARKER: return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP: return "push-group";
    case GL_DEBUG_TYPE_POP_GROUP: return "pop-group";
    default: return "other";
  }
}

// The GlContext current on this thread. glvnd refuses to make a GLX (GLFW)
// context current while an EGL one is (BadAccess) and vice versa, so switching
// releases the previous context first.
thread_local GlContext* tCurrent = nullptr;

// glfwTerminate destroys every window: terminate only when the last one goes.
int gGlfwWindows = 0;

// eglGetPlatformDisplay returns the same display to every headless context,
// and eglTerminate ends every context on it: terminate only when the last of
// this process's contexts on it goes (a second GlContext must not end the first).
std::mutex gDisplayMutex;
std::map<EGLDisplay, int> gDisplayUsers;
void useDisplay(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(gDisplayMutex);
  ++gDisplayUsers[d];
}
bool displayInUse(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(gDisplayMutex);
  return gDisplayUsers.count(d) > 0;
}
bool lastDisplayUser(EGLDisplay d) {
  std::lock_guard<std::mutex> lock(gDisplayMutex);
  auto it = gDisplayUsers.find(d);
  if (it == gDisplayUsers.end() || --it->second > 0) return it == gDisplayUsers.end();
  gDisplayUsers.erase(it);
  return true;
}

// GLFW reports errors through a callback; keep the last one for exceptions.
std::string& glfwLastError() {
  static std::string e;
  return e;
}
void glfwErrorCallback(int code, const char* description) {
  glfwLastError() = description ? description : ("GLFW error " + std::to_string(code));
}

}  // namespace

struct DebugCallbackAccess {
  static void GLAPIENTRY callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                  const GLchar* message, const void* user) {
    auto* self = static_cast<GlContext*>(const_cast<void*>(user));
    std::string msg = length >= 0 ? std::string(message, static_cast<size_t>(length)) : std::string(message);
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    self->debugMessages_.fetch_add(1);
    if (type == GL_DEBUG_TYPE_ERROR && source != GL_DEBUG_SOURCE_SHADER_COMPILER) {
      self->debugErrors_.fetch_add(1);
      {
        std::lock_guard<std::mutex> lock(self->impl_->mutex);
        self->impl_->lastError = msg;
      }
      spdlog::error("GL [{} {} {}]: {}", debugSourceName(source), debugTypeName(type), id, msg);
    } else if (type == GL_DEBUG_TYPE_PERFORMANCE) {
      spdlog::warn("GL [{} {} {}]: {}", debugSourceName(source), debugTypeName(type), id, msg);
    } else if (severity != GL_DEBUG_SEVERITY_NOTIFICATION || spdlog::should_log(spdlog::level::trace)) {
      spdlog::debug("GL [{} {} {}]: {}", debugSourceName(source), debugTypeName(type), id, msg);
    }
  }
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {}

void GlContext::releaseCurrent() {
  if (tCurrent != this) return;
  if (impl_->window)
    glfwMakeContextCurrent(nullptr);
  else if (impl_->display != EGL_NO_DISPLAY)
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  tCurrent = nullptr;
}

GlContext::~GlContext() {
  bool wasCurrent = tCurrent == this;
  if (wasCurrent) tCurrent = nullptr;
  if (impl_->window) {
    glfwDestroyWindow(impl_->window);
    if (--gGlfwWindows == 0) glfwTerminate();
  }
  if (impl_->display != EGL_NO_DISPLAY) {
    if (wasCurrent) eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (impl_->context != EGL_NO_CONTEXT) eglDestroyContext(impl_->display, impl_->context);
    if (lastDisplayUser(impl_->display)) eglTerminate(impl_->display);
  }
}

namespace {

// EGL's devices (EGL_EXT_device_enumeration), each with its handle and what
// eglQueryDeviceStringEXT says about it.
struct EglDevices {
  std::vector<EGLDeviceEXT> handles;
  std::vector<gl::EglDeviceInfo> infos;
  std::string note;  // why there are none, where EGL cannot enumerate
};

EglDevices enumerateEglDevices(const char* clientExts) {
  EglDevices out;
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  EGLint count = 0;
  if (!hasEglExtension(clientExts, "EGL_EXT_device_enumeration") ||
      !hasEglExtension(clientExts, "EGL_EXT_platform_device") || !queryDevices || !queryString) {
    out.note = " (this EGL lacks EGL_EXT_device_enumeration or EGL_EXT_platform_device)";
    return out;
  }
  if (!queryDevices(0, nullptr, &count) || count <= 0) return out;
  out.handles.resize(static_cast<size_t>(count));
  if (!queryDevices(count, out.handles.data(), &count)) count = 0;
  out.handles.resize(static_cast<size_t>(std::max<EGLint>(count, 0)));
  for (EGLDeviceEXT device : out.handles) {
    const char* exts = queryString(device, EGL_EXTENSIONS);
    gl::EglDeviceInfo info = gl::eglDeviceFromExtensions(exts ? exts : "");
    // Only what the device's extensions promise: a query it does not know is an EGL error.
    auto query = [&](EGLint name, const char* extension) -> std::string {
      if (!hasEglExtension(exts, extension)) return {};
      const char* s = queryString(device, name);
      return s ? s : "";
    };
    // NVIDIA in a container often has no DRM node it can open: the device
    // still works through EGL_PLATFORM_DEVICE_EXT, the node is only a label.
    info.drmNode = query(EGL_DRM_RENDER_NODE_FILE_EXT, "EGL_EXT_device_drm_render_node");
    if (info.drmNode.empty()) info.drmNode = query(EGL_DRM_DEVICE_FILE_EXT, "EGL_EXT_device_drm");
    info.vendor = query(EGL_VENDOR, "EGL_EXT_device_query_name");
    info.renderer = query(EGL_RENDERER_EXT, "EGL_EXT_device_query_name");
    out.infos.push_back(std::move(info));
  }
  eglGetError();  // a failed string query leaves nothing for the next caller to misread
  return out;
}

// A 4.5 core context on an initialised display; EGL_NO_CONTEXT with the
// reason appended to `why`.
EGLContext createOnDisplay(EGLDisplay display, const std::string& name, bool debug, std::string& why) {
  const char* dpyExts = eglQueryString(display, EGL_EXTENSIONS);
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why += name + ": no desktop OpenGL (" + eglErrorName(eglGetError()) + "); ";
    return EGL_NO_CONTEXT;
  }
  if (!hasEglExtension(dpyExts, "EGL_KHR_surfaceless_context")) {
    why += name + ": lacks EGL_KHR_surfaceless_context, needed for headless rendering; ";
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!hasEglExtension(dpyExts, "EGL_KHR_no_config_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &n) || n < 1) {
      why += name + ": no config supports desktop OpenGL; ";
      return EGL_NO_CONTEXT;
    }
  }
  std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
  if (debug) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
  attribs.push_back(EGL_NONE);
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
  if (context == EGL_NO_CONTEXT) {
    why += name + ": cannot create an OpenGL 4.5 core context (" + eglErrorName(eglGetError()) + "); ";
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why += name + ": eglMakeCurrent failed (" + eglErrorName(eglGetError()) + "); ";
    eglDestroyContext(display, context);
    return EGL_NO_CONTEXT;
  }
  return context;
}

// Makes im's headless context current: on the device RGRAPH_EGL_DEVICE names,
// else on the first hardware device that gives a 4.5 context, else as before
// devices were chosen (Mesa surfaceless, any device, the default display).
void openHeadless(GlContext::Impl& im, bool debug) {
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EglDevices devices = getPlatformDisplay ? enumerateEglDevices(clientExts)
                                          : EglDevices{{}, {}, " (this EGL lacks eglGetPlatformDisplayEXT)"};
  const char* requested = std::getenv("RGRAPH_EGL_DEVICE");
  const gl::EglDeviceChoice choice = gl::chooseEglDevice(devices.infos, requested);
  if (!choice.error.empty()) throw RuntimeError(choice.error + devices.note);

  std::string why;
  auto attempt = [&](EGLDisplay d, const std::string& name) -> bool {
    if (d == EGL_NO_DISPLAY) {
      why += name + ": no display (" + eglErrorName(eglGetError()) + "); ";
      return false;
    }
    const bool shared = displayInUse(d);  // another GlContext of this process is on it
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) {
      why += name + ": eglInitialize failed (" + eglErrorName(eglGetError()) + "); ";
      return false;
    }
    im.context = createOnDisplay(d, name, debug, why);
    if (im.context == EGL_NO_CONTEXT) {
      if (!shared) eglTerminate(d);
      return false;
    }
    im.display = d;
    useDisplay(d);
    return true;
  };
  auto attemptDevice = [&](size_t i) -> bool {
    im.platform = "egl-device";
    im.eglDevice = static_cast<int>(i);
    im.eglDeviceDescription = gl::describeEglDevice(devices.infos[i]);
    if (attempt(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices.handles[i], nullptr),
                "egl-device " + std::to_string(i) + " (" + im.eglDeviceDescription + ")"))
      return true;
    im.eglDevice = -1;
    im.eglDeviceDescription.clear();
    return false;
  };

  std::vector<bool> tried(devices.handles.size(), false);
  for (size_t i : choice.candidates) {
    tried[i] = true;
    if (attemptDevice(i)) return;
  }
  if (!choice.fallback) throw RuntimeError("RGRAPH_EGL_DEVICE=" + std::string(requested) + ": " + why);

  if (getPlatformDisplay && hasEglExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    im.platform = "egl-surfaceless";
    if (attempt(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), im.platform)) return;
  } else {
    why += "egl-surfaceless: EGL_MESA_platform_surfaceless not supported; ";
  }
  for (size_t i = 0; i < devices.handles.size(); ++i)
    if (!tried[i] && attemptDevice(i)) return;
  if (devices.handles.empty()) why += "egl-device: no EGL devices" + devices.note + "; ";
  im.platform = "egl-default";
  if (attempt(eglGetDisplay(EGL_DEFAULT_DISPLAY), im.platform)) return;
  im.platform.clear();
  throw RuntimeError("cannot create a headless OpenGL 4.5 core context: " + why);
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create(const ContextOptions& options) {
  tuneMalloc();
  GlContext* previous = tCurrent;
  try {
    return createImpl(options);
  } catch (...) {
    // Leave the thread as it was: the previous context current again.
    if (previous && tCurrent != previous) previous->makeCurrent();
    throw;
  }
}

std::unique_ptr<GlContext> GlContext::createImpl(const ContextOptions& options) {
  std::unique_ptr<GlContext> ctx(new GlContext());
  Impl& im = *ctx->impl_;

  if (tCurrent) tCurrent->releaseCurrent();

  if (options.window) {
    glfwSetErrorCallback(glfwErrorCallback);
    if (!glfwInit())
      throw RuntimeError("cannot open a window: glfwInit failed: " + glfwLastError() +
                         " (run headless, or under xvfb-run)");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* w = glfwCreateWindow(static_cast<int>(options.width), static_cast<int>(options.height),
                                     options.title.c_str(), nullptr, nullptr);
    if (!w) {
      std::string e = glfwLastError();
      if (gGlfwWindows == 0) glfwTerminate();
      throw RuntimeError("cannot create a window with an OpenGL 4.5 core context: " + e);
    }
    im.window = w;
    ++gGlfwWindows;
    im.platform = "glfw";
    glfwMakeContextCurrent(w);
    glfwSwapInterval(0);
  } else {
    openHeadless(im, options.debug);
  }

  tCurrent = ctx.get();

  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    throw RuntimeError("OpenGL 4.5 is required, the context reports " + glString(GL_VERSION));

  im.vendor = glString(GL_VENDOR);
  im.renderer = glString(GL_RENDERER);
  im.version = glString(GL_VERSION);
  if (options.debug) ctx->installDebugCallback();
  spdlog::debug("GL context: {}", describeContext(ctx->device()));
  return ctx;
}

void GlContext::installDebugCallback() {
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(&DebugCallbackAccess::callback, this);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  if (!(flags & GL_CONTEXT_FLAG_DEBUG_BIT)) spdlog::debug("GL context is not a debug context; KHR_debug may be quiet");
}

void GlContext::makeCurrent() {
  if (tCurrent == this) return;
  if (tCurrent) tCurrent->releaseCurrent();
  tCurrent = this;
  if (impl_->window) {
    glfwMakeContextCurrent(impl_->window);
  } else if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context)) {
    throw RuntimeError("eglMakeCurrent failed: " + eglErrorName(eglGetError()));
  }
}

std::string GlContext::renderer() const { return impl_->renderer; }
std::string GlContext::version() const { return impl_->version; }
std::string GlContext::vendor() const { return impl_->vendor; }
std::string GlContext::platform() const { return impl_->platform; }

ContextDevice GlContext::device() const {
  return {impl_->platform, impl_->eglDevice, impl_->eglDeviceDescription, impl_->vendor, impl_->renderer,
          impl_->version};
}

std::string describeContext(const ContextDevice& d) {
  std::string s = d.renderer + ", OpenGL " + d.version + ", " + d.vendor + " (" + d.platform;
  if (d.eglDevice >= 0) s += " " + std::to_string(d.eglDevice) + ": " + d.eglDeviceDescription;
  return s + ")";
}

bool hasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

bool GlContext::isSoftware() const {
  std::string r = renderer();
  for (const char* s : {"llvmpipe", "softpipe", "swrast", "SWR", "Software Rasterizer"})
    if (r.find(s) != std::string::npos) return true;
  return false;
}

bool GlContext::hasWindow() const { return impl_->window != nullptr; }

void GlContext::swapBuffers() {
  if (impl_->window) glfwSwapBuffers(impl_->window);
}

bool GlContext::shouldClose() { return impl_->window ? glfwWindowShouldClose(impl_->window) != 0 : false; }

void GlContext::pollEvents() {
  if (impl_->window) glfwPollEvents();
}

Extent GlContext::windowFramebufferSize() const {
  if (!impl_->window) return {};
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
}

std::string GlContext::lastDebugError() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->lastError;
}

}  // namespace rgraph
