// `rgraph render`: run a pipeline headless and write its output image.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <iostream>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "cli_outputs.h"
#include "commands.h"
#include "median.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/image.h"
#include "rgraph/output_file.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/plugin.h"
#include "rgraph/renderer.h"
#include "rgraph/scene.h"

namespace rgraph::cli {
namespace {

// Pass times of the frames whose timings came in (each once: with GPU timer
// queries they arrive frames later, and a frame that found its queries busy
// has none), medians over those frames.
struct PassTimes {
  std::map<std::string, std::vector<double>> ms;
  std::vector<std::string> order;
  std::optional<uint64_t> lastFrame;  // the last frame recorded
  size_t frames = 0;

  void take(const Renderer& renderer) {
    const std::optional<uint64_t> frame = renderer.timingsFrame();
    if (!frame || frame == lastFrame) return;
    lastFrame = frame;
    ++frames;
    for (const auto& t : renderer.timings()) {
      if (!ms.count(t.name)) order.push_back(t.name);
      ms[t.name].push_back(t.ms);
    }
  }
};

void writeStats(const std::string& path, const std::vector<double>& frameMs, const PassTimes& passTimes, bool cpuTimed,
                const Plan& plan, const ContextDevice& device) {
  const auto& passMs = passTimes.ms;
  const auto& passOrder = passTimes.order;
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& name : passOrder) passes.push_back({{"name", name}, {"ms", median(passMs.at(name))}});
  auto [mn, mx] = std::minmax_element(frameMs.begin(), frameMs.end());
  nlohmann::json stats = {{"frame_ms", median(frameMs)},
                          {"frame_ms_min", *mn},
                          {"frame_ms_max", *mx},
                          {"frames", frameMs.size()},
                          {"pass_clock", cpuTimed ? "cpu_glfinish" : "gl_time_elapsed"},
                          {"timed_frames", passTimes.frames},
                          {"passes", passes},
                          {"memory", memoryJson(plan)},
                          {"context", contextJson(device)}};
  writeOutputFile(path, stats.dump(2) + "\n", "stats file");
}

// "px,py,pz,tx,ty,tz[,fovDeg]": the camera at (px,py,pz) looking at (tx,ty,tz).
std::optional<Camera> parseCamera(const std::string& text, Camera camera, std::string& error) {
  std::vector<float> v;
  if (text.empty() || text.back() == ',') {  // getline drops an empty last item
    error = "--camera '" + text + "': a number is missing (expected px,py,pz,tx,ty,tz[,fovDeg])";
    return std::nullopt;
  }
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const float f = std::strtof(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(f)) {
      error = "--camera '" + text + "': '" + item + "' is not a number (expected px,py,pz,tx,ty,tz[,fovDeg])";
      return std::nullopt;
    }
    v.push_back(f);
  }
  if (v.size() != 6 && v.size() != 7) {
    error = "--camera '" + text + "': expected 6 or 7 numbers (px,py,pz,tx,ty,tz[,fovDeg]), got " +
            std::to_string(v.size());
    return std::nullopt;
  }
  camera.position = glm::vec3(v[0], v[1], v[2]);
  camera.target = glm::vec3(v[3], v[4], v[5]);
  if (v.size() == 7) {
    if (!(v[6] > 0.0f && v[6] < 180.0f)) {
      error = "--camera '" + text + "': the field of view must be between 0 and 180 degrees";
      return std::nullopt;
    }
    camera.fovY = v[6];
  }
  return camera;
}

// --cut "K[,K...]": the 0-based frames that follow a camera cut, each below
// `frames`. nullopt with `error` set when one is not such a number.
std::optional<std::set<uint32_t>> parseCuts(const std::string& text, uint32_t frames, std::string& error) {
  std::set<uint32_t> cuts;
  std::stringstream in(text);
  std::string item;
  const std::string expected =
      " (expected K[,K...]: 0-based frame numbers below --frames " + std::to_string(frames) + ")";
  while (std::getline(in, item, ',')) {
    const bool digits =
        !item.empty() && std::all_of(item.begin(), item.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits) {
      error = "--cut '" + text + "': '" + item + "' is not a frame number" + expected;
      return std::nullopt;
    }
    // A number of any length is a frame number; past 9 digits it is beyond every --frames.
    const uint32_t k = item.size() <= 9 ? static_cast<uint32_t>(std::stoul(item)) : frames;
    if (k >= frames) {
      error = "--cut '" + text + "': frame " + item + " is beyond --frames " + std::to_string(frames) +
              " (the frames are 0 to " + std::to_string(frames - 1) + ")";
      return std::nullopt;
    }
    cuts.insert(k);
  }
  if (text.empty() || text.back() == ',') {
    error = "--cut '" + text + "': a frame number is missing" + expected;
    return std::nullopt;
  }
  return cuts;
}

}  // namespace

// Everything through the public renderer API (rgraph/renderer.h), as a
// program embedding rgraph would: this command only adds the context, the
// PNG and the statistics.
int runRender(const RenderOptions& options) {
  // The frame options first: a mistake in them costs no loading.
  const uint32_t frames = std::max<uint32_t>(1, options.frames);
  std::set<uint32_t> cuts;
  if (options.cuts) {
    std::string error;
    std::optional<std::set<uint32_t>> parsed = parseCuts(*options.cuts, frames, error);
    if (!parsed) {
      std::cerr << "error: " << error << "\n";
      return kExitFailure;
    }
    cuts = std::move(*parsed);
  }
  float orbit = 0.0f;
  if (options.orbit) {
    char* end = nullptr;
    orbit = std::strtof(options.orbit->c_str(), &end);
    if (options.orbit->empty() || *end != '\0' || !std::isfinite(orbit)) {
      std::cerr << "error: --orbit '" << *options.orbit << "': not a number of degrees per frame\n";
      return kExitFailure;
    }
  }

  HazardModes hazards;
  if (const std::string error = parseHazardModes(options.hazards, hazards); !error.empty()) {
    std::cerr << "error: --hazards: " << error << "\n";
    return kExitFailure;
  }

  // The animation clock: --time >= 0 seconds, --fps > 0 frames per second.
  auto number = [](const std::optional<std::string>& text, double& out) {
    if (!text) return true;
    char* end = nullptr;
    out = std::strtod(text->c_str(), &end);
    return !text->empty() && *end == '\0' && std::isfinite(out);
  };
  double time = 0.0, fps = 0.0;
  if (!number(options.time, time) || time < 0.0) {
    std::cerr << "error: --time '" << *options.time << "': not a number of seconds >= 0\n";
    return kExitFailure;
  }
  if (!number(options.fps, fps) || (options.fps && fps <= 0.0)) {
    std::cerr << "error: --fps '" << *options.fps << "': not a number of frames per second > 0\n";
    return kExitFailure;
  }

  const std::string pipelinePath = options.pipeline.empty() ? defaultPipelinePath() : options.pipeline;
  // Before any work: no output replaces an input or another output, and each can be written.
  std::vector<NamedPath> inputs = {{"the pipeline", pipelinePath}, {"--scene", options.scene}};
  const std::vector<NamedPath> outputs = {{"--out", options.out}, {"--stats", options.stats}};
  if (!checkOutputs(inputs, outputs)) return kExitFailure;
  RendererOptions rendererOptions = cli::rendererOptions();  // the command's pass types and --plugin-path
  rendererOptions.size = Extent{options.size.width, options.size.height};
  rendererOptions.maxTextureSize = options.size.maxTextureSize;
  rendererOptions.maxTextureSizeOrigin = compileOptions(0, 0, options.size.maxTextureSize).maxTextureSizeOrigin;
  rendererOptions.maxMemoryBytes = options.size.maxMemoryBytes;
  rendererOptions.maxMemoryOrigin = "--max-memory";
  rendererOptions.runChecks = options.checks;
  rendererOptions.hazards = hazards;
  Diagnostics diags;
  std::unique_ptr<Renderer> renderer = Renderer::fromFile(pipelinePath, rendererOptions, diags);
  // Render refuses what validate refuses, before any GL work: the graph at
  // this size (the device's own texture limit is checked when it is built),
  // the pass types' checks and the shader checks (cached on disk).
  printDiagnostics(diags);
  if (!renderer) return kExitFailure;

  try {
    const std::string sceneSpec = options.scene.empty() ? std::string("learnopengl:overview") : options.scene;
    std::shared_ptr<RenderScene> scene = RenderScene::load(sceneSpec);
    if (!options.environment.empty()) scene->setEnvironment(environmentFromSpec(options.environment));
    std::optional<Camera> camera;
    if (!options.camera.empty()) {
      std::string error;
      camera = parseCamera(options.camera, scene->scene().camera, error);
      if (!camera) {
        std::cerr << "error: " << error << "\n";
        return kExitFailure;
      }
    }

    ContextOptions ctxOptions;
    ctxOptions.window = options.window;
    ctxOptions.width = options.size.width;
    ctxOptions.height = options.size.height;
    auto context = GlContext::create(ctxOptions);
    spdlog::info("GL context: {}", describeContext(context->device()));

    renderer->setScene(scene);
    const Camera start = camera ? *camera : scene->scene().camera;
    renderer->setCamera(start);
    renderer->setSize(Extent{options.size.width, options.size.height});

    std::vector<double> frameMs;
    PassTimes passTimes;
    for (uint32_t i = 0; i < frames; ++i) {
      if (cuts.count(i)) renderer->cameraCut();
      if (orbit != 0.0f) renderer->setCamera(orbitCamera(start, orbit * static_cast<float>(i)));
      scene->setTime(fps > 0.0 ? time + static_cast<double>(i) / fps : time);
      auto t0 = std::chrono::steady_clock::now();
      // One render per frame (a second would be a frame of its own to the
      // history and the jitter): in a window, with the copy into it.
      if (context->hasWindow()) {
        const Extent fb = context->windowFramebufferSize();
        renderer->render(0, Viewport{0, 0, fb.width, fb.height});
      } else {
        renderer->render();
      }
      auto t1 = std::chrono::steady_clock::now();
      if (i == 0)  // "Model no more than the scene needs": what the adaptation changed.
        for (const auto& note : renderer->adaptNotes()) spdlog::info("{}", note);
      frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      passTimes.take(*renderer);
      if (context->hasWindow()) {  // show it
        context->swapBuffers();
        context->pollEvents();
      }
    }
    if (context->debugErrorCount() > 0)
      spdlog::warn("{} OpenGL errors were reported while rendering", context->debugErrorCount());

    // Again with what the pipeline turned out to read: its shader files and plugins.
    for (const auto& file : renderer->watchedFiles()) inputs.push_back({"the pipeline's file", file});
    for (const auto& plugin : renderer->loadedPlugins()) inputs.push_back({"the plugin", plugin});
    if (!checkOutputs(inputs, outputs)) return kExitFailure;
    const Extent extent = renderer->outputExtent();
    writePng(options.out, extent.width, extent.height, renderer->readOutputRGBA8());
    std::cout << "wrote " << options.out << " (" << extent.width << "x" << extent.height << ", " << frames
              << (frames == 1 ? " frame" : " frames") << ", median " << median(frameMs) << " ms)\n";
    if (!options.stats.empty()) {
      renderer->collectTimings(/*wait=*/true);  // the last frames' queries, after the run (no-op on CPU timing)
      passTimes.take(*renderer);
      writeStats(options.stats, frameMs, passTimes, renderer->cpuTimed(), renderer->plan(),
                 context->device());
    }
  } catch (const LocatedError& e) {
    std::cerr << e.what() << "\n";  // `FILE:LINE: error: ...` already
    return kExitFailure;
  } catch (const RuntimeError& e) {
    std::cerr << errorLine(e.what()) << "\n";  // a scene file's `FILE:L:C: ...` reads `FILE:L:C: error: ...`
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace rgraph::cli
