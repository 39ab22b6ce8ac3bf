// embed_glfw: rgraph inside a program that owns its window, its GL context and
// its framebuffer. Every frame it moves its own camera, lets rgraph run the
// pipeline into a texture the program created (imported as the pipeline's
// "output" resource), then draws with its own shader: that texture over the
// window, a picture-in-picture of a G-buffer target, and an orange frame.
//
//   embed_glfw [--pipeline FILE] [--scene SPEC] [--size WxH] [--frames N]
//              [--resize-to WxH] [--screenshot OUT.png] [--print-camera]
//              [--import-mismatch]
//
// Every failure prints "error: ..." and exits 1.
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>  // GL 4.5 core prototypes (rgraph::rgraph defines GL_GLEXT_PROTOTYPES)
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rgraph/gl/executor.h"  // Renderer::executor()->textureOf: the inset's G-buffer target
#include "rgraph/image.h"        // rgraph::writePng
#include "rgraph/renderer.h"

namespace {

// The picture, for a window of W x H pixels: rgraph's image 1:1 everywhere but
// an orange frame kBorder pixels wide, and the G-buffer normals at a quarter
// size in the lower-right corner, inside the frame.
constexpr int kBorder = 8;
constexpr float kFrameColour[3] = {1.0f, 0.5f, 0.0f};
constexpr const char* kOutputResource = "output";  // rgba8, declared by the pipeline
constexpr const char* kInsetResource = "gNormal";
constexpr float kOrbitRadiansPerFrame = 0.02f;

struct Args {
  std::string pipeline = EMBED_DEFAULT_PIPELINE;
  std::string scene = "learnopengl:overview";
  int width = 640, height = 360;
  long frames = 0;                        // 0: until the window is closed
  int resizeWidth = 0, resizeHeight = 0;  // --resize-to: the window's size from frame frames / 2 on
  std::string screenshot;
  bool printCamera = false;
  bool importMismatch = false;
};

[[noreturn]] void fail(const std::string& message) { throw std::runtime_error(message); }

long number(const std::string& text, const std::string& what, long lo, long hi) {
  size_t used = 0;
  long v = 0;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size() || v < lo || v > hi)
    fail(what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" + text +
         "'");
  return v;
}

void parseSize(const std::string& option, const std::string& v, int& w, int& h) {
  const size_t x = v.find('x');
  if (x == std::string::npos) fail(option + " must be WxH (for example 640x360), not '" + v + "'");
  w = int(number(v.substr(0, x), option + " width", 2 * kBorder + 4, 8192));
  h = int(number(v.substr(x + 1), option + " height", 2 * kBorder + 4, 8192));
}

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] {
      if (i + 1 >= argc) fail(arg + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--pipeline")
      a.pipeline = value();
    else if (arg == "--scene")
      a.scene = value();
    else if (arg == "--frames")
      a.frames = number(value(), "--frames", 0, 1000000);
    else if (arg == "--screenshot")
      a.screenshot = value();
    else if (arg == "--print-camera")
      a.printCamera = true;
    else if (arg == "--import-mismatch")
      a.importMismatch = true;
    else if (arg == "--size")
      parseSize(arg, value(), a.width, a.height);
    else if (arg == "--resize-to")
      parseSize(arg, value(), a.resizeWidth, a.resizeHeight);
    else
      fail("unknown argument '" + arg + "' (options: --pipeline FILE --scene SPEC --size WxH --frames N " +
           "--resize-to WxH --screenshot OUT.png --print-camera --import-mismatch)");
  }
  if (!a.screenshot.empty() && a.frames == 0) fail("--screenshot needs --frames N (it is taken of the last frame)");
  if (a.resizeWidth && a.frames < 2) fail("--resize-to needs --frames N of 2 or more (it resizes at frame N / 2)");
  return a;
}

// The camera is a function of the frame number only: the scene's own camera,
// orbiting its target about the vertical axis.
rgraph::Camera cameraAt(const rgraph::Camera& start, long frame) {
  const float a = kOrbitRadiansPerFrame * float(frame), c = std::cos(a), s = std::sin(a);
  const glm::vec3 d = start.position - start.target;
  rgraph::Camera camera = start;
  camera.position = start.target + glm::vec3(c * d.x + s * d.z, d.y, c * d.z - s * d.x);
  return camera;
}

// One triangle over the viewport; the texture drawn with colour * remap.x + remap.y.
const char* kVertexShader = R"(#version 450 core
out vec2 uv;
void main() {
  uv = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(2.0 * uv - 1.0, 0.0, 1.0);
})";
const char* kFragmentShader = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D image;
layout(location = 0) uniform vec2 remap;
out vec4 colour;
void main() { colour = vec4(texture(image, uv).rgb * remap.x + remap.y, 1.0); })";

GLuint compileProgram() {
  const GLuint program = glCreateProgram();
  for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, kVertexShader}, {GL_FRAGMENT_SHADER, kFragmentShader}}) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
    glDeleteShader(shader);  // freed with the program
  }
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    fail(std::string("the composite shader does not link: ") + log);
  }
  return program;
}

// The texture rgraph renders into: ours, rgba8 at the output size (half that
// with --import-mismatch, which importTexture refuses).
GLuint importTarget(rgraph::Renderer& renderer, int w, int h, bool mismatch) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA8, mismatch ? w / 2 : w, mismatch ? h / 2 : h);
  try {
    renderer.importTexture(kOutputResource, texture);
  } catch (...) {
    glDeleteTextures(1, &texture);
    throw;
  }
  return texture;
}

// The back buffer as a PNG (GL rows go bottom-up, PNG rows top-down).
void writeScreenshot(const std::string& path, int w, int h) {
  std::vector<uint8_t> pixels(size_t(w) * h * 4), png(pixels.size());
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  for (int y = 0; y < h; ++y) std::copy_n(&pixels[size_t(h - 1 - y) * w * 4], size_t(w) * 4, &png[size_t(y) * w * 4]);
  rgraph::writePng(path, uint32_t(w), uint32_t(h), png);
}

int run(const Args& args) {
  glfwSetErrorCallback([](int, const char* what) { std::cerr << "GLFW: " << what << "\n"; });
  if (!glfwInit()) fail("cannot start GLFW (no display? run it under xvfb-run -a)");
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;  // last, after the window and everything in its context
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  std::unique_ptr<GLFWwindow, void (*)(GLFWwindow*)> window(
      glfwCreateWindow(args.width, args.height, "rgraph inside a GLFW window", nullptr, nullptr), glfwDestroyWindow);
  if (!window) fail("cannot open a window with an OpenGL 4.5 core context");
  glfwMakeContextCurrent(window.get());

  // rgraph in our context: diagnostics name file:line:col and the JSON path.
  int w = 0, h = 0;
  glfwGetFramebufferSize(window.get(), &w, &h);
  rgraph::RendererOptions options;
  options.size = {uint32_t(w), uint32_t(h)};
  rgraph::Diagnostics diags;
  auto renderer = rgraph::Renderer::fromFile(args.pipeline, options, diags);
  for (const auto& d : diags) std::cerr << rgraph::formatDiagnostic(d) << "\n";
  if (!renderer) fail("the pipeline " + args.pipeline + " has errors");
  renderer->setScene(rgraph::RenderScene::load(args.scene));
  const rgraph::Camera start = renderer->camera();  // the scene's camera
  GLuint target = importTarget(*renderer, w, h, args.importMismatch);

  // Our own GL objects: the composite program, an empty VAO, a nearest sampler
  // (1:1 copies stay exact).
  const GLuint program = compileProgram();
  GLuint vao = 0, sampler = 0;
  glCreateVertexArrays(1, &vao);
  glCreateSamplers(1, &sampler);
  glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  rgraph::Camera camera = start;
  for (long frame = 0; !glfwWindowShouldClose(window.get()) && (args.frames == 0 || frame < args.frames); ++frame) {
    if (args.resizeWidth && frame == args.frames / 2)
      glfwSetWindowSize(window.get(), args.resizeWidth, args.resizeHeight);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window.get(), &fw, &fh);
    if ((fw != w || fh != h) && fw > 2 * kBorder && fh > 2 * kBorder) {  // resized: textures of the new size
      w = fw, h = fh;
      renderer->setSize({uint32_t(w), uint32_t(h)});
      glDeleteTextures(1, &target);
      target = importTarget(*renderer, w, h, false);
    }
    camera = cameraAt(start, frame);
    renderer->setCamera(camera);
    renderer->render();  // into `target`; our GL state comes back as we left it

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glClearColor(kFrameColour[0], kFrameColour[1], kFrameColour[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program);
    glBindVertexArray(vao);
    glBindSampler(0, sampler);
    glEnable(GL_SCISSOR_TEST);
    // rgraph's image, pixel for pixel, inside the frame.
    glViewport(0, 0, w, h);
    glScissor(kBorder, kBorder, w - 2 * kBorder, h - 2 * kBorder);
    glBindTextureUnit(0, target);
    glUniform2f(0, 1.0f, 0.0f);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // The inset: a G-buffer target rgraph owns, normals mapped to colours.
    if (GLuint normals = renderer->executor()->textureOf(kInsetResource)) {
      glViewport(w - kBorder - w / 4, kBorder, w / 4, h / 4);
      glScissor(w - kBorder - w / 4, kBorder, w / 4, h / 4);
      glBindTextureUnit(0, normals);
      glUniform2f(0, 0.5f, 0.5f);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_SCISSOR_TEST);
    if (!args.screenshot.empty() && frame + 1 == args.frames) writeScreenshot(args.screenshot, w, h);
    glfwSwapBuffers(window.get());
    glfwPollEvents();
  }
  if (args.printCamera)  // as `rgraph render --camera` takes it
    std::printf("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", camera.position.x, camera.position.y, camera.position.z,
                camera.target.x, camera.target.y, camera.target.z, camera.fovY);

  glDeleteSamplers(1, &sampler);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(program);
  glDeleteTextures(1, &target);
  renderer.reset();  // rgraph's objects go while the context is current
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parseArgs(argc, argv));
  } catch (const std::exception& e) {  // rgraph::RuntimeError included
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
