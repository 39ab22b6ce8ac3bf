// rgraph_editor: a small level editor on rgraph/renderer.h. It loads a level
// (a scene file), edits its models per frame through RenderScene's objects
// API (scripted, or with the keyboard), renders with a pipeline that uses a
// pass type of its own (registered in-process), draws a grid and a gizmo over
// rgraph's frame with plain GL, depth-tested against rgraph's depth, and
// writes the level as it stands as a scene file `rgraph render` draws the same.
//
//   rgraph_editor [--level FILE] [--pipeline FILE] [--size WxH] [--frames N]
//                 [--script FILE] [--do "FRAME COMMAND ..."]... [--no-tint]
//                 [--no-overlay] [--screenshot OUT.png] [--rgraph-out OUT.png]
//                 [--save-state OUT.json] [--play FPS]
//
// --play FPS: the animation clock (skinned and animated glTF models) runs,
// 1/FPS seconds a frame from the last `time` step (0 without one).
//
// Keys: Tab selects the next model, the arrows move it on the ground, a click
// picks (selectAt). Every failure prints "error: ..." and exits 1.
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "editor_pipeline.h"
#include "level.h"
#include "overlay.h"
#include "rgraph/image.h"
#include "rgraph/renderer.h"
#include "script.h"

namespace {

// The editor's look (its own pass): warm, so its view is never taken for the game's.
constexpr glm::vec4 kTint{1.0f, 0.9f, 0.8f, 1.0f};
constexpr float kNudge = 0.25f;  // an arrow key moves the selection this far

struct Args {
  std::string level = EDITOR_DEFAULT_LEVEL;
  std::string pipeline = EDITOR_DEFAULT_PIPELINE;
  int width = 960, height = 540;
  long frames = 0;  // 0: until the window is closed
  std::vector<editor::Step> steps;
  bool tint = true, overlay = true;
  std::string screenshot, rgraphOut, saveState;
  long playFps = 0;  // 0: the clock moves only with `time` steps
};

[[noreturn]] void fail(const std::string& message) { throw std::runtime_error(message); }

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

long number(const std::string& text, const std::string& what, long lo, long hi) {
  size_t used = 0;
  long v = 0;
  try {
    v = std::stol(text, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != text.size() || v < lo || v > hi)
    fail(what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" + text + "'");
  return v;
}

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] {
      if (i + 1 >= argc) fail(arg + " needs a value");
      return std::string(argv[++i]);
    };
    if (arg == "--level") a.level = value();
    else if (arg == "--pipeline") a.pipeline = value();
    else if (arg == "--frames") a.frames = number(value(), "--frames", 0, 1000000);
    else if (arg == "--script") {
      const std::string file = value();
      for (editor::Step& s : editor::parseScript(readFile(file), file)) a.steps.push_back(std::move(s));
    } else if (arg == "--do") {
      const std::string line = value();
      a.steps.push_back(editor::parseStep(line, "--do '" + line + "'"));
    } else if (arg == "--no-tint") a.tint = false;
    else if (arg == "--no-overlay") a.overlay = false;
    else if (arg == "--screenshot") a.screenshot = value();
    else if (arg == "--rgraph-out") a.rgraphOut = value();
    else if (arg == "--save-state") a.saveState = value();
    else if (arg == "--play") a.playFps = number(value(), "--play", 1, 1000);
    else if (arg == "--size") {
      const std::string v = value();
      const size_t x = v.find('x');
      if (x == std::string::npos) fail("--size must be WxH (for example 960x540), not '" + v + "'");
      a.width = int(number(v.substr(0, x), "--size width", 16, 8192));
      a.height = int(number(v.substr(x + 1), "--size height", 16, 8192));
    } else
      fail("unknown argument '" + arg + "' (options: --level FILE --pipeline FILE --size WxH --frames N " +
           "--script FILE --do STEP --no-tint --no-overlay --screenshot PNG --rgraph-out PNG --save-state JSON --play FPS)");
  }
  const bool captures = !a.screenshot.empty() || !a.rgraphOut.empty() || !a.saveState.empty();
  if (captures && a.frames == 0) fail("--screenshot, --rgraph-out and --save-state need --frames N (the last frame)");
  for (const editor::Step& s : a.steps)
    if (a.frames && s.frame >= a.frames)
      fail(s.where + ": frame " + std::to_string(s.frame) + " is never drawn (--frames " + std::to_string(a.frames) + ")");
  return a;
}

// The renderer: the pipeline file as it is (--no-tint), or with the editor's
// own pass after it, from a registry that knows that pass (RendererOptions::registry).
std::unique_ptr<rgraph::Renderer> makeRenderer(const Args& args, const rgraph::PassRegistry& types, int w, int h) {
  rgraph::RendererOptions options;
  options.size = {uint32_t(w), uint32_t(h)};
  options.registry = &types;
  options.keepDepth = true;  // the overlay's depth test reads it
  options.picking = true;    // object ids for clicks (8 bytes a pixel; selectAt)
  rgraph::Diagnostics diags;
  std::unique_ptr<rgraph::Renderer> renderer;
  if (args.tint) {
    // A pipeline that is not JSON goes to rgraph unchanged: its message names the line and column.
    std::string text = readFile(args.pipeline), name = args.pipeline;
    try {
      text = editor::withTint(text, kTint);
      name += " + editor_tint";  // line numbers are the rewritten text's now
    } catch (const std::runtime_error& e) {
      if (std::string(e.what()).find("not JSON") == std::string::npos) fail(args.pipeline + ": " + e.what());
    }
    const std::string folder = args.pipeline.substr(0, args.pipeline.find_last_of('/') + 1);
    renderer = rgraph::Renderer::fromJson(text, name, options, diags, folder);
  } else {
    renderer = rgraph::Renderer::fromFile(args.pipeline, options, diags);
  }
  for (const auto& d : diags) std::cerr << rgraph::formatDiagnostic(d) << "\n";
  if (!renderer) fail("the pipeline " + args.pipeline + " has errors");
  return renderer;
}

// The window's back buffer (GL rows go bottom-up, PNG rows top-down).
void writeScreenshot(const std::string& path, int w, int h) {
  std::vector<uint8_t> pixels(size_t(w) * h * 4), png(pixels.size());
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  for (int y = 0; y < h; ++y) std::copy_n(&pixels[size_t(h - 1 - y) * w * 4], size_t(w) * 4, &png[size_t(y) * w * 4]);
  rgraph::writePng(path, uint32_t(w), uint32_t(h), png);
}

// Keyboard and mouse: edits made the way a script's steps are.
void onKey(GLFWwindow* window, int key, int, int action, int) {
  auto& s = *static_cast<editor::Session*>(glfwGetWindowUserPointer(window));
  if (action == GLFW_RELEASE) return;
  try {
    if (key == GLFW_KEY_TAB) {  // the next model still there
      const size_t n = s.level.modelCount();
      for (size_t i = 1; i <= n; ++i) {
        const size_t next = (s.selected.value_or(n - 1) + i) % n;
        if (s.level.exists(next)) {
          s.selected = next;
          break;
        }
      }
      return;
    }
    const glm::vec3 step = key == GLFW_KEY_LEFT    ? glm::vec3(-kNudge, 0, 0)
                           : key == GLFW_KEY_RIGHT ? glm::vec3(kNudge, 0, 0)
                           : key == GLFW_KEY_UP    ? glm::vec3(0, 0, -kNudge)
                           : key == GLFW_KEY_DOWN  ? glm::vec3(0, 0, kNudge)
                                                   : glm::vec3(0);
    if (s.selected && step != glm::vec3(0)) {
      editor::Placement p = s.level.placement(*s.selected);
      p.translation += step;
      s.level.setPlacement(*s.selected, p);
    }
  } catch (const std::exception& e) {
    std::cerr << "note: " << e.what() << "\n";  // interactive: say so and go on
  }
}

void onClick(GLFWwindow* window, int button, int action, int) {
  if (button != GLFW_MOUSE_BUTTON_LEFT || action != GLFW_PRESS) return;
  auto& s = *static_cast<editor::Session*>(glfwGetWindowUserPointer(window));
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  try {
    editor::selectAt(s.renderer, int(x), int(y));  // window coordinates: pixels unless the screen scales them
  } catch (const std::exception& e) {
    std::cerr << "note: " << e.what() << "\n";
  }
}

int run(const Args& args) {
  editor::Level level(args.level);  // read before a window opens: a mistake in it costs none
  glfwSetErrorCallback([](int, const char* what) { std::cerr << "GLFW: " << what << "\n"; });
  if (!glfwInit()) fail("cannot start GLFW (no display? run it under xvfb-run -a)");
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;  // last, after the window and everything in its context
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);  // the state file's size is the window's
  std::unique_ptr<GLFWwindow, void (*)(GLFWwindow*)> window(
      glfwCreateWindow(args.width, args.height, "rgraph editor", nullptr, nullptr), glfwDestroyWindow);
  if (!window) fail("cannot open a window with an OpenGL 4.5 core context");
  glfwMakeContextCurrent(window.get());
  int w = 0, h = 0;
  glfwGetFramebufferSize(window.get(), &w, &h);

  const rgraph::PassRegistry types = editor::editorPassTypes(EDITOR_SHADER_DIR);
  auto renderer = makeRenderer(args, types, w, h);
  renderer->setScene(level.scene());
  editor::Session session{level, *renderer, std::nullopt};
  glfwSetWindowUserPointer(window.get(), &session);
  glfwSetKeyCallback(window.get(), onKey);
  glfwSetMouseButtonCallback(window.get(), onClick);
  std::optional<editor::Overlay> overlay;
  if (args.overlay) overlay.emplace();

  for (long frame = 0; !glfwWindowShouldClose(window.get()) && (args.frames == 0 || frame < args.frames); ++frame) {
    if (args.playFps > 0 && frame > 0) {  // before this frame's steps: a `time` step sets the clock outright
      session.clock += 1.0 / double(args.playFps);
      editor::advanceClock(*level.scene(), session.clock);
    }
    for (const editor::Step& step : args.steps)
      if (step.frame == frame) editor::apply(step, session);
    renderer->render(0);  // rgraph's frame into the window; our GL state comes back as we left it
    if (const auto picked = editor::pickedModel(*renderer, level, session.pickTaken)) {  // a click's answer
      session.selected = *picked;
      if (*picked) std::printf("selected model %zu\n", **picked);
      else std::printf("selected nothing\n");
    }
    if (overlay) {
      const rgraph::Camera& camera = renderer->camera();
      const glm::mat4 viewProjection = camera.projection(float(w) / float(h)) * camera.view();
      std::optional<glm::vec3> gizmo;
      if (session.selected) gizmo = level.placement(*session.selected).translation;
      glViewport(0, 0, w, h);
      overlay->draw(viewProjection, renderer->outputDepthTexture(), gizmo);
    }
    if (frame + 1 == args.frames) {
      if (!args.screenshot.empty()) writeScreenshot(args.screenshot, w, h);
      if (!args.rgraphOut.empty()) rgraph::writePng(args.rgraphOut, uint32_t(w), uint32_t(h), renderer->readOutputRGBA8());
      if (!args.saveState.empty()) {
        std::ofstream out(args.saveState);
        out << level.state(renderer->camera()).dump(2) << "\n";
        if (!out) fail("cannot write " + args.saveState);
      }
    }
    glfwSwapBuffers(window.get());
    glfwPollEvents();
  }
  overlay.reset();
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
