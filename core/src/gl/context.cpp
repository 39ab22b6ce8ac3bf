#include "rgraph/gl/context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <malloc.h>
#include <spdlog/spdlog.h>

#include <cstring>
#include <map>
#include <mutex>
#include <vector>

#include "rgraph/error.h"

namespace rgraph {

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLFWwindow* window = nullptr;
  std::string platform;
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

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

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

// Returns an initialised display or EGL_NO_DISPLAY; appends what failed to `why`.
EGLDisplay openDisplay(std::string& platform, std::string& why) {
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto tryInit = [&](EGLDisplay d, const char* name) -> bool {
    if (d == EGL_NO_DISPLAY) {
      why += std::string(name) + ": no display (" + eglErrorName(eglGetError()) + "); ";
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) {
      why += std::string(name) + ": eglInitialize failed (" + eglErrorName(eglGetError()) + "); ";
      return false;
    }
    platform = name;
    return true;
  };

  if (getPlatformDisplay && hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (tryInit(d, "egl-surfaceless")) return d;
  } else {
    why += "egl-surfaceless: EGL_MESA_platform_surfaceless not supported; ";
  }

  if (getPlatformDisplay && hasExtension(clientExts, "EGL_EXT_platform_device")) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices && queryDevices(16, devices, &count) && count > 0) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (tryInit(d, "egl-device")) return d;
      }
    } else {
      why += "egl-device: no EGL devices; ";
    }
  } else {
    why += "egl-device: EGL_EXT_platform_device not supported; ";
  }

  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (tryInit(d, "egl-default")) return d;
  return EGL_NO_DISPLAY;
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
    std::string why;
    EGLDisplay display = openDisplay(im.platform, why);
    if (display == EGL_NO_DISPLAY) throw RuntimeError("cannot open an EGL display: " + why);
    im.display = display;
    useDisplay(display);
    const char* dpyExts = eglQueryString(display, EGL_EXTENSIONS);
    if (!eglBindAPI(EGL_OPENGL_API))
      throw RuntimeError("EGL (" + im.platform + ") does not support desktop OpenGL: " +
                         eglErrorName(eglGetError()));
    if (!hasExtension(dpyExts, "EGL_KHR_surfaceless_context"))
      throw RuntimeError("EGL (" + im.platform + ") lacks EGL_KHR_surfaceless_context, needed for headless rendering");

    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(dpyExts, "EGL_KHR_no_config_context")) {
      const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint n = 0;
      if (!eglChooseConfig(display, attribs, &config, 1, &n) || n < 1)
        throw RuntimeError("EGL (" + im.platform + "): no config supports desktop OpenGL");
    }
    std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
    if (options.debug) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
    attribs.push_back(EGL_NONE);
    im.context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
    if (im.context == EGL_NO_CONTEXT)
      throw RuntimeError("EGL (" + im.platform + "): cannot create an OpenGL 4.5 core context: " +
                         eglErrorName(eglGetError()));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, im.context))
      throw RuntimeError("EGL (" + im.platform + "): eglMakeCurrent failed: " + eglErrorName(eglGetError()));
  }

  tCurrent = ctx.get();

  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5))
    throw RuntimeError("OpenGL 4.5 is required, the context reports " + glString(GL_VERSION));

  if (options.debug) ctx->installDebugCallback();
  spdlog::debug("GL context ({}): {} / {}", im.platform, glString(GL_RENDERER), glString(GL_VERSION));
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

std::string GlContext::renderer() const { return glString(GL_RENDERER); }
std::string GlContext::version() const { return glString(GL_VERSION); }
std::string GlContext::vendor() const { return glString(GL_VENDOR); }
std::string GlContext::platform() const { return impl_->platform; }

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
