#include <GL/glcorearb.h>

#include <cstdlib>
#include <optional>

#include "gl_test_util.h"
#include "rgraph/error.h"
#include "rgraph/gl/format.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::test;

TEST_F(GlTest, HeadlessContextIsGl45Core) {
  EXPECT_FALSE(ctx().hasWindow());
  EXPECT_FALSE(ctx().renderer().empty());
  EXPECT_NE(ctx().version().find("4.5"), std::string::npos) << ctx().version();
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
  if (ctx().renderer().find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(ctx().isSoftware());
  }
  EXPECT_EQ(ctx().windowFramebufferSize(), (Extent{0, 0}));
  EXPECT_FALSE(ctx().shouldClose());
  EXPECT_FALSE(ctx().platform().empty());
}

TEST_F(GlTest, DebugCallbackCountsGlErrors) {
  uint64_t before = ctx().debugErrorCount();
  glBindTexture(0x1234, 0);  // GL_INVALID_ENUM
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  EXPECT_EQ(ctx().debugErrorCount(), before + 1);
  EXPECT_FALSE(ctx().lastDebugError().empty());
  errorsAtStart = ctx().debugErrorCount();  // the error above was intended
}

TEST_F(GlTest, WindowWithoutDisplayFailsCleanly) {
  if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) GTEST_SKIP() << "a display is available";
  ContextOptions o;
  o.window = true;
  try {
    auto w = GlContext::create(o);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("window"), std::string::npos) << e.what();
  }
  glContext().makeCurrent();
}

TEST_F(GlTest, ObjectWrappersCountLiveObjects) {
  using gl::ObjectKind;
  int64_t tex = gl::liveObjects(ObjectKind::texture);
  int64_t fbo = gl::liveObjects(ObjectKind::framebuffer);
  {
    gl::Texture t = gl::createTexture2D(Format::rgba16f, {8, 8});
    EXPECT_NE(t.id(), 0u);
    EXPECT_EQ(gl::liveObjects(ObjectKind::texture), tex + 1);
    gl::Texture moved = std::move(t);
    EXPECT_EQ(t.id(), 0u);
    EXPECT_EQ(gl::liveObjects(ObjectKind::texture), tex + 1);
    gl::Framebuffer f = gl::createFramebuffer();
    EXPECT_EQ(gl::liveObjects(ObjectKind::framebuffer), fbo + 1);
    f = gl::createFramebuffer();  // the first one is deleted
    EXPECT_EQ(gl::liveObjects(ObjectKind::framebuffer), fbo + 1);
    EXPECT_TRUE(glIsTexture(moved.id()));
  }
  EXPECT_EQ(gl::liveObjects(ObjectKind::texture), tex);
  EXPECT_EQ(gl::liveObjects(ObjectKind::framebuffer), fbo);
}

TEST_F(GlTest, EveryFormatCreatesATexture) {
  for (Format f : allFormats()) {
    gl::Texture t = gl::createTexture2D(f, {4, 4});
    GLint internal = 0;
    glGetTextureLevelParameteriv(t.id(), 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    EXPECT_EQ(static_cast<unsigned>(internal), gl::glFormat(f).internalFormat) << formatName(f);
  }
  gl::Texture ms = gl::createTexture2D(Format::rgba8, {4, 4}, 1, 4);
  GLint samples = 0;
  glGetTextureLevelParameteriv(ms.id(), 0, GL_TEXTURE_SAMPLES, &samples);
  EXPECT_EQ(samples, 4);
  gl::Texture mips = gl::createTexture2D(Format::rgba8, {16, 4}, 0);
  GLint levels = 0;
  glGetTextureParameteriv(mips.id(), GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  EXPECT_EQ(levels, 5);
}

// Runs only with a display (e.g. under `xvfb-run -a`); skipped headless.
TEST_F(GlTest, WindowContextRendersAGraph) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a to test windows)";
  ContextOptions o;
  o.window = true;
  o.width = 40;
  o.height = 30;
  {
    auto win = GlContext::create(o);
    EXPECT_TRUE(win->hasWindow());
    EXPECT_EQ(win->platform(), "glfw");
    EXPECT_EQ(win->windowFramebufferSize(), (Extent{40, 30}));
    {
      ShaderLibrary lib;
      GraphBuilder g;
      g.output("out");
      g.pass("gradient", "fullscreen", {writeUse("color", Access::color_attachment, "out")},
             params({{"shader", std::string("gradient.frag")}}));
      Executor exec(g.config(), processRegistry(), lib);
      exec.resize(win->windowFramebufferSize());
      exec.renderFrame();
      std::string first;
      EXPECT_EQ(gradientMismatches(exec.readOutputRGBA8(), {40, 30}, &first), 0u) << first;
      win->pollEvents();
      win->swapBuffers();
      EXPECT_FALSE(win->shouldClose());
    }
    EXPECT_EQ(win->debugErrorCount(), 0u) << win->lastDebugError();
  }
  glContext().makeCurrent();
}

namespace {
// $RGRAPH_EGL_DEVICE set (or unset: null) for one scope, as it was afterwards.
class EglDeviceVariable {
 public:
  explicit EglDeviceVariable(const char* value) {
    if (const char* old = std::getenv("RGRAPH_EGL_DEVICE")) saved_ = old;
    if (value)
      setenv("RGRAPH_EGL_DEVICE", value, 1);
    else
      unsetenv("RGRAPH_EGL_DEVICE");
  }
  ~EglDeviceVariable() {
    if (saved_)
      setenv("RGRAPH_EGL_DEVICE", saved_->c_str(), 1);
    else
      unsetenv("RGRAPH_EGL_DEVICE");
  }

 private:
  std::optional<std::string> saved_;
};
}  // namespace

// The context says where it runs: the GL strings it was made with, and the
// EGL device exactly when it is on the device platform. A GPU is found
// through the device platform (what a Mesa surfaceless display would hide).
TEST_F(GlTest, ContextNamesItsDevice) {
  std::unique_ptr<GlContext> c;
  {
    EglDeviceVariable unset(nullptr);
    c = GlContext::create();
  }
  const ContextDevice d = c->device();
  auto glString = [](GLenum name) { return std::string(reinterpret_cast<const char*>(glGetString(name))); };
  EXPECT_EQ(d.vendor, glString(GL_VENDOR));
  EXPECT_EQ(d.renderer, glString(GL_RENDERER));
  EXPECT_EQ(d.version, glString(GL_VERSION));
  EXPECT_EQ(d.platform, c->platform());
  EXPECT_EQ(d.eglDevice >= 0, d.platform == "egl-device") << describeContext(d);
  EXPECT_EQ(d.eglDeviceDescription.empty(), d.eglDevice < 0) << describeContext(d);
  if (!c->isSoftware()) {
    EXPECT_EQ(d.platform, "egl-device") << "a GPU, not through the device platform";
  } else if (d.eglDevice >= 0) {
    EXPECT_EQ(d.eglDeviceDescription, "software (EGL_MESA_device_software)");
  }
  EXPECT_NE(describeContext(d).find(d.renderer), std::string::npos);
  c.reset();
  glContext().makeCurrent();
  EXPECT_EQ(ctx().renderer(), glString(GL_RENDERER));
}

// RGRAPH_EGL_DEVICE=0: device 0 of the enumeration, whatever it is (here
// Mesa's software device), on the device platform.
TEST_F(GlTest, EglDeviceVariablePicksTheDevice) {
  std::unique_ptr<GlContext> c;
  {
    EglDeviceVariable zero("0");
    c = GlContext::create();
  }
  EXPECT_EQ(c->platform(), "egl-device");
  EXPECT_EQ(c->device().eglDevice, 0);
  EXPECT_FALSE(c->device().eglDeviceDescription.empty());
  EXPECT_NE(c->version().find("4.5"), std::string::npos) << c->version();
  c.reset();
  glContext().makeCurrent();
}

TEST_F(GlTest, EglDeviceVariableOutOfRangeListsTheDevices) {
  for (const char* bad : {"999", "gpu"}) {
    SCOPED_TRACE(bad);
    EglDeviceVariable v(bad);
    try {
      auto c = GlContext::create();
      FAIL() << "expected RuntimeError, got " << describeContext(c->device());
    } catch (const RuntimeError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("RGRAPH_EGL_DEVICE=", 0), 0u) << what;
      EXPECT_NE(what.find("EGL devices found: 0: "), std::string::npos) << what;
    }
  }
  glContext().makeCurrent();
}
