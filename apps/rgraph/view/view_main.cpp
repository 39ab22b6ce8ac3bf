// `rgraph view`: a GLFW window (GL 4.5 core) showing a pipeline's output, Dear
// ImGui panels over it, camera controls, live reload of the pipeline, its
// shaders and the scene file, and a script runner for automation. Built only
// on the public renderer API (rgraph/renderer.h). docs/viewer.md.
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "../cli_common.h"
#include "../cli_outputs.h"
#include "../commands.h"
#include "../median.h"
#include "rgraph/error.h"
#include "rgraph/gl/objects.h"
#include "rgraph/image.h"
#include "rgraph/output_file.h"
#include "view_app.h"
#include "view_panels.h"
#include "view_reload.h"
#include "view_script.h"
#include "view_selection.h"

namespace rgraph::cli {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPollInterval = std::chrono::milliseconds(250);

// The window and its GL context; open() after the GL-free checks so that bad input opens nothing.
struct Window {
  GLFWwindow* handle = nullptr;
  bool glfwStarted = false;
  bool imguiStarted = false;
  void open(uint32_t width, uint32_t height) {
    glfwSetErrorCallback([](int, const char* what) { std::cerr << "GLFW: " << what << "\n"; });
    if (!glfwInit()) throw RuntimeError("cannot start GLFW (no display? run it under xvfb-run -a)");
    glfwStarted = true;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    handle = glfwCreateWindow(int(width), int(height), "rgraph view", nullptr, nullptr);
    if (!handle) throw RuntimeError("cannot open a GL 4.5 core window");
    glfwMakeContextCurrent(handle);
    glfwSwapInterval(0);  // the frame rate is the renderer's, not the display's
    // Set before ImGui installs its callbacks, which then call this one too.
    glfwSetScrollCallback(handle, [](GLFWwindow* w, double, double dy) {
      if (auto* input = static_cast<view::InputState*>(glfwGetWindowUserPointer(w))) input->wheel += float(dy);
    });
  }
  void startImgui() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui_ImplGlfw_InitForOpenGL(handle, true);
    ImGui_ImplOpenGL3_Init("#version 450");
    imguiStarted = true;
  }
  ~Window() {
    if (imguiStarted) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    if (handle) glfwDestroyWindow(handle);
    if (glfwStarted) glfwTerminate();
  }
};

// The back buffer (the frame as it will be shown, UI included when on) as a PNG.
void screenshot(const std::string& path, int w, int h) {
  std::vector<uint8_t> pixels(size_t(w) * h * 4), flipped(pixels.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const size_t row = size_t(w) * 4;
  for (int y = 0; y < h; ++y) std::copy_n(&pixels[size_t(h - 1 - y) * row], row, &flipped[size_t(y) * row]);
  writePng(path, uint32_t(w), uint32_t(h), flipped);
}

std::vector<std::string> errorLines(const Diagnostics& diags) {
  std::vector<std::string> lines;
  for (const auto& d : diags)
    if (d.severity == Severity::error) lines.push_back(formatDiagnostic(d));
  return lines;
}

// formatDiagnostic without its "error: ", after a script line's own: `s.txt:3: error: param ...: p.json:20:18: ...`.
std::string afterScriptLine(const Diagnostic& d) {
  std::string f = formatDiagnostic(d);
  const size_t at = f.find("error: ");
  if (at != std::string::npos && (at == 0 || f.compare(at - 2, 2, ": ") == 0)) f.erase(at, 7);
  return f;
}

// Everything one session holds; members are destroyed before the window (declared in runView first).
class Viewer {
 public:
  Viewer(const ViewOptions& options, std::vector<view::ScriptCommand> script, Window& window,
         std::unique_ptr<Renderer> renderer, std::shared_ptr<RenderScene> scene, std::string pipelinePath)
      : options_(options),
        script_(std::move(script)),
        window_(window),
        renderer_(std::move(renderer)),
        scene_(std::move(scene)),
        editor_(std::move(pipelinePath)),
        status_(options.status) {
    ui_ = script_.empty();  // scripted runs start without panels: screenshots show the pipeline's output
    camera_.setHome(renderer_->camera());
    sceneFile_ = std::filesystem::is_regular_file(options.scene) ? options.scene : "";
    inspector_.attach(*renderer_);
  }
  ~Viewer() { inspector_.detach(); }
  void run();

 private:
  bool runScript(std::string& shot);  // false: quit
  void pollFiles();
  void reloadPipeline();
  void reloadScene();
  void applyParam(const view::ScriptCommand& c);
  void applyPanelEdit(const std::string& text);
  void renderFrame(Extent fb);
  void drawUi();
  void report(const std::string& event, bool ok, const std::vector<std::string>& errors);
  void writeStats() const;
  // Picking: asks about window pixel (x, y) (framebuffer pixels, from the top-left); takeAnswer prints
  // and selects what the renderer answers, a frame or two later.
  void requestPick(uint32_t x, uint32_t y, int line);
  void takeAnswer();

  const ViewOptions& options_;
  std::vector<view::ScriptCommand> script_;
  size_t next_ = 0;
  long waitFrames_ = 0;
  std::string waitFile_;
  Window& window_;
  std::unique_ptr<Renderer> renderer_;
  std::shared_ptr<RenderScene> scene_;
  view::ParamEditor editor_;
  view::ResourceInspector inspector_;
  view::StatusFile status_;
  view::FileWatcher pipelineWatch_, sceneWatch_;
  view::CameraController camera_;
  view::InputState input_;
  std::string sceneFile_;
  std::vector<std::string> errors_;  // the last failed reload's diagnostics, shown in red until one succeeds
  std::string renderError_;          // the refusal reported for the frames failing now ("" while they render)
  Extent refusedSize_;               // a window size the renderer refused: not tried again every frame
  Extent goodSize_;                  // the size of the last frame drawn
  std::vector<double> uiOnMs_, uiOffMs_;
  bool ui_ = true;
  // The animation clock (RenderScene::setTime): advanced by each frame's wall time while playing.
  bool playing_ = false;
  double clock_ = 0.0;
  std::string showTab_;  // a script's `panel`: the tab drawPanels brings to the front
  bool pickPending_ = false;
  std::optional<PickResult> selected_;  // the Selection panel's object (the last answer)
};

void Viewer::requestPick(uint32_t x, uint32_t y, int line) {
  try {
    renderer_->requestPick(x, y);
    pickPending_ = true;
  } catch (const RuntimeError& e) {  // outside the window: said, the script goes on
    const std::string where = line > 0 ? options_.script + ":" + std::to_string(line) + ": error: " : "error: ";
    report("pick", false, {where + e.what()});
  }
}

void Viewer::takeAnswer() {
  if (!pickPending_) return;
  std::optional<PickResult> answer = renderer_->pickResult();
  if (!answer) return;
  pickPending_ = false;
  selected_ = std::move(answer);
  for (const std::string& line : view::describePick(*scene_, *selected_)) std::cout << "rgraph view: " << line << "\n";
  std::cout.flush();
}

void Viewer::report(const std::string& event, bool ok, const std::vector<std::string>& errors) {
  if (ok)
    errors_.clear();
  else
    errors_ = errors;
  for (const auto& e : errors) std::cerr << e << "\n";
  status_.write(event, ok, errors);
}

void Viewer::reloadPipeline() {
  Diagnostics diags;
  const int64_t before = gl::createdObjectsTotal();
  const bool ok = renderer_->reload(diags);
  std::cerr << "rgraph view: pipeline reload " << (ok ? "ok" : "failed") << ", " << gl::createdObjectsTotal() - before
            << " GL objects created\n";
  if (ok) editor_.reread();
  report("reload", ok, errorLines(diags));
}

void Viewer::reloadScene() {
  try {
    auto scene = RenderScene::load(sceneFile_);
    const Camera camera = renderer_->camera();  // an edit of the scene does not move the viewer's camera
    renderer_->setScene(scene);
    renderer_->setCamera(camera);
    scene_ = scene;
    selected_.reset();  // its ids were the old scene's
    pickPending_ = false;
    report("reload", true, {});
  } catch (const std::exception& e) {  // the old scene keeps rendering
    report("reload", false, {cli::errorLine(e.what())});
  }
}

void Viewer::pollFiles() {
  pipelineWatch_.watch(renderer_->watchedFiles());  // new shader files join with their current times
  if (pipelineWatch_.changed()) reloadPipeline();
  if (!sceneFile_.empty()) {
    sceneWatch_.watch({sceneFile_});
    if (sceneWatch_.changed()) reloadScene();
  }
}

// Every message names the script line; the renderer's also name the param's place in the pipeline file
// (ParamEditor::inFile), not one in the text the editor made.
void Viewer::applyParam(const view::ScriptCommand& c) {
  const std::string where = options_.script + ":" + std::to_string(c.line) + ": error: ";
  std::string error;
  const std::optional<std::string> text =
      editor_.withParam(c.words[0], c.words[1], c.words[2], renderer_->passTypes(), error);
  if (!text) return report("param", false, {where + error});
  Diagnostics diags;
  if (renderer_->reloadJson(*text, diags, editor_.path())) {
    editor_.accept(*text);
    return report("param", true, {});
  }
  std::vector<std::string> lines;
  std::string joined;
  for (const auto& d : editor_.inFile(diags)) {
    if (d.severity != Severity::error) continue;
    lines.push_back(where + "param " + c.words[0] + " " + c.words[1] + ": " + afterScriptLine(d));
    joined += formatDiagnostic(d) + "\n";
  }
  editor_.reject(joined);
  report("param", false, lines);
}

void Viewer::applyPanelEdit(const std::string& text) {
  Diagnostics diags;
  if (renderer_->reloadJson(text, diags, editor_.path())) return editor_.accept(text);
  std::string joined;
  for (const auto& l : errorLines(editor_.inFile(diags))) joined += l + "\n";
  editor_.reject(joined);
}

// A frame the device (or --max-memory) refuses is reported once, not every frame, and the last good frame
// stays on screen; a size refused goes back to the last good one (Renderer::setSize), the window too.
void Viewer::renderFrame(Extent fb) {
  try {
    renderer_->render(0, Viewport{0, 0, fb.width, fb.height});
    goodSize_ = fb;
    if (!renderError_.empty()) {
      renderError_.clear();
      report("render", true, {});
    }
    return;
  } catch (const RuntimeError& e) {
    const std::string line = cli::errorLine(e.what());
    if (line != renderError_) report("render", false, {line});
    renderError_ = line;
  }
  // The renderer goes back to the last good size by itself when the size is what it refused; whatever
  // else failed at a new size (the device running out of memory), the viewer goes back too.
  if (goodSize_.width > 0 && renderer_->size() != goodSize_) renderer_->setSize(goodSize_);
  const Extent good = renderer_->size();
  if (good != fb) {
    refusedSize_ = fb;
    glfwSetWindowSize(window_.handle, int(good.width), int(good.height));
  }
  renderer_->present(0, Viewport{0, 0, good.width, good.height});
}

// Runs commands up to the next wait or screenshot; a screenshot is taken once this frame is drawn.
bool Viewer::runScript(std::string& shot) {
  using K = view::ScriptCommand::Kind;
  if (waitFrames_ > 0) {
    --waitFrames_;
    return true;
  }
  if (!waitFile_.empty()) {
    if (!std::filesystem::exists(waitFile_)) return true;
    waitFile_.clear();
  }
  while (next_ < script_.size()) {
    const view::ScriptCommand& c = script_[next_++];
    const auto& n = c.numbers;
    switch (c.kind) {
      case K::Camera: {
        Camera cam = camera_.camera();
        cam.position = {n[0], n[1], n[2]};
        cam.target = {n[3], n[4], n[5]};
        if (n.size() == 7) cam.fovY = n[6];
        camera_.set(cam);
        break;
      }
      case K::Wait:
        waitFrames_ = long(n[0]);
        return true;
      case K::WaitFile:
        waitFile_ = c.words[0];
        return true;
      case K::Screenshot:
        shot = c.words[0];
        return true;
      case K::Ui:
        ui_ = c.words[0] == "on";
        break;
      case K::Param:
        applyParam(c);
        break;
      case K::Inspect:
        inspector_.select(c.words[0]);
        inspector_.setLayer(uint32_t(n[0]));
        inspector_.setMip(uint32_t(n[1]));
        break;
      case K::Panel:
        showTab_ = c.words[0];
        break;
      case K::Pick:
        requestPick(uint32_t(n[0]), uint32_t(n[1]), c.line);
        break;
      case K::Resize:
        glfwSetWindowSize(window_.handle, int(n[0]), int(n[1]));
        renderer_->setSize(Extent{uint32_t(n[0]), uint32_t(n[1])});
        break;
      case K::Time:
        clock_ = n[0];
        break;
      case K::Play:
        playing_ = true;
        break;
      case K::Pause:
        playing_ = false;
        break;
      case K::Quit:
        return false;
    }
  }
  return true;
}

void Viewer::drawUi() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // Lower left, below the panels' left window (view::drawPanels).
  ImGui::SetNextWindowPos(ImVec2(10, ImGui::GetIO().DisplaySize.y - 10), ImGuiCond_FirstUseEver, ImVec2(0, 1));
  ImGui::Begin("Camera");
  const Camera& c = camera_.camera();
  ImGui::Text("position %.3f %.3f %.3f", c.position.x, c.position.y, c.position.z);
  ImGui::Text("target   %.3f %.3f %.3f", c.target.x, c.target.y, c.target.z);
  ImGui::Text("fov %.1f", c.fovY);
  if (ImGui::Button("Copy")) glfwSetClipboardString(window_.handle, ("--camera " + camera_.cameraArgument()).c_str());
  ImGui::SameLine();
  ImGui::TextDisabled("orbit: left drag, fly: right drag + WASD/QE, zoom: wheel, R: reset, F1: UI");
  if (!scene_->scene().animation.empty()) {  // glTF animations, skins, morph targets: the clock
    if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
    ImGui::SameLine();
    if (ImGui::Button("Rewind")) clock_ = 0.0;
    ImGui::SameLine();
    ImGui::Text("time %.2f s", clock_);
  }
  ImGui::End();
  if (!errors_.empty()) {
    ImGui::Begin("Reload errors");
    for (const auto& e : errors_) ImGui::TextColored(ImVec4(1.0f, 0.3f, 0.3f, 1.0f), "%s", e.c_str());
    ImGui::TextWrapped("The last good pipeline keeps rendering.");
    ImGui::End();
  }
  if (std::optional<std::string> text = view::drawPanels(*renderer_, editor_, inspector_, &showTab_))
    applyPanelEdit(*text);
  view::drawSelection(scene_.get(), selected_);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Viewer::writeStats() const {
  if (options_.stats.empty()) return;
  const double on = median(uiOnMs_), off = median(uiOffMs_);
  nlohmann::json stats = {{"ui_on_ms", on},
                          {"ui_off_ms", off},
                          {"ui_on_frames", uiOnMs_.size()},
                          {"ui_off_frames", uiOffMs_.size()},
                          {"ui_share", on > 0 ? (on - off) / on : 0.0}};
  writeOutputFile(options_.stats, stats.dump(2) + "\n", "stats file");
}

void Viewer::run() {
  GLFWwindow* win = window_.handle;
  glfwGetCursorPos(win, &input_.lastX, &input_.lastY);
  glfwSetWindowUserPointer(win, &input_);
  auto last = Clock::now(), lastPoll = last;
  bool first = true;
  while (!glfwWindowShouldClose(win)) {
    glfwPollEvents();
    const auto now = Clock::now();
    const float seconds = std::chrono::duration<float>(now - last).count();
    last = now;
    if (!first && now - lastPoll >= kPollInterval) {
      lastPoll = now;
      pollFiles();
    }
    std::string shot;
    if (!runScript(shot)) break;
    const ImGuiIO& io = ImGui::GetIO();
    view::handleInput(win, input_, camera_, ui_ && io.WantCaptureMouse, ui_ && io.WantCaptureKeyboard, seconds, ui_);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win, &fw, &fh);
    if (fw <= 0 || fh <= 0) continue;  // minimised
    const Extent fb{uint32_t(fw), uint32_t(fh)};
    if (fb != refusedSize_) refusedSize_ = {};  // the window left the refused size: another size may be tried
    if (fb != renderer_->size() && fb != refusedSize_) renderer_->setSize(fb);
    renderer_->setCamera(camera_.camera());
    if (input_.clicked) {  // window coordinates to framebuffer pixels (they differ on high-DPI screens)
      input_.clicked = false;
      int ww = 0, wh = 0;
      glfwGetWindowSize(win, &ww, &wh);
      if (ww > 0 && wh > 0 && input_.clickX >= 0 && input_.clickY >= 0)
        requestPick(uint32_t(input_.clickX * fw / ww), uint32_t(input_.clickY * fh / wh), 0);
    }
    if (playing_) clock_ += seconds;
    scene_->setTime(clock_);
    const auto t0 = Clock::now();
    renderFrame(fb);
    takeAnswer();
    if (first) {  // the baseline before anyone reads the load line (and may then edit a file)
      pipelineWatch_.watch(renderer_->watchedFiles());
      if (!sceneFile_.empty()) sceneWatch_.watch({sceneFile_});
      report("load", true, {});
      first = false;
    }
    if (ui_) drawUi();
    if (!options_.stats.empty()) {  // the frame's own cost: wait for the GPU before stopping the clock
      glFinish();
      (ui_ ? uiOnMs_ : uiOffMs_).push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    if (!shot.empty()) {  // the frame as drawn: the last good one, at its size, when this one was refused
      glfwGetFramebufferSize(win, &fw, &fh);
      screenshot(shot, std::min(fw, int(renderer_->size().width)), std::min(fh, int(renderer_->size().height)));
    }
    glfwSwapBuffers(win);
  }
  writeStats();
}

}  // namespace

int runView(const ViewOptions& options) {
  std::vector<view::ScriptCommand> script;
  if (!options.script.empty()) {
    std::string error;
    script = view::loadScript(options.script, error);
    if (!error.empty()) {
      std::cerr << error << "\n";
      return kExitFailure;
    }
  }
  const std::string pipelinePath = options.pipeline.empty() ? defaultPipelinePath() : options.pipeline;
  // Before any work: no output replaces an input (a --status file that is the
  // pipeline reloaded it at every line) or another output (cli_outputs.h).
  std::vector<NamedPath> outputs = {{"--status", options.status}, {"--stats", options.stats}};
  for (const auto& c : script)
    if (c.kind == view::ScriptCommand::Kind::Screenshot)
      outputs.push_back({options.script + ":" + std::to_string(c.line) + ": screenshot", c.words.at(0), true});
  if (!checkOutputs({{"the pipeline", pipelinePath}, {"--scene", options.scene}, {"--script", options.script}},
                    outputs))
    return kExitFailure;
  RendererOptions rendererOptions = cli::rendererOptions();  // the command's pass types and --plugin-path
  rendererOptions.size = Extent{options.size.width, options.size.height};
  rendererOptions.maxTextureSize = options.size.maxTextureSize;
  rendererOptions.maxTextureSizeOrigin = compileOptions(0, 0, options.size.maxTextureSize).maxTextureSizeOrigin;
  rendererOptions.maxMemoryBytes = options.size.maxMemoryBytes;
  rendererOptions.picking = true;  // a click selects: the object ids, 8 bytes a pixel (docs/viewer.md)
  rendererOptions.maxMemoryOrigin = "--max-memory";
  Window window;  // first: destroyed last, after everything that holds GL objects
  Diagnostics diags;
  std::unique_ptr<Renderer> renderer = Renderer::fromFile(pipelinePath, rendererOptions, diags);
  printDiagnostics(diags);
  if (!renderer) return kExitFailure;
  std::shared_ptr<RenderScene> scene =
      RenderScene::load(options.scene.empty() ? std::string("learnopengl:overview") : options.scene);
  window.open(options.size.width, options.size.height);
  window.startImgui();
  renderer->setScene(scene);
  Viewer viewer(options, std::move(script), window, std::move(renderer), scene, pipelinePath);
  viewer.run();
  return kExitOk;
}

}  // namespace rgraph::cli
