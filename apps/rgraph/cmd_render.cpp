// `rgraph render`: run a pipeline headless and write its output image.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "commands.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/image.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace rgraph::cli {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void writeStats(const std::string& path, const std::vector<double>& frameMs,
                const std::map<std::string, std::vector<double>>& passMs, const std::vector<std::string>& passOrder,
                const Plan& plan) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& name : passOrder) passes.push_back({{"name", name}, {"ms", median(passMs.at(name))}});
  auto [mn, mx] = std::minmax_element(frameMs.begin(), frameMs.end());
  nlohmann::json stats = {{"frame_ms", median(frameMs)},
                          {"frame_ms_min", *mn},
                          {"frame_ms_max", *mx},
                          {"frames", frameMs.size()},
                          {"passes", passes},
                          {"memory", {{"naive_bytes", plan.naiveBytes}, {"allocated_bytes", plan.allocatedBytes}}}};
  std::ofstream f(path);
  if (!f) throw RuntimeError("cannot write stats file '" + path + "'");
  f << stats.dump(2) << "\n";
}

}  // namespace

int runRender(const RenderOptions& options) {
  const std::string pipelinePath = options.pipeline.empty() ? defaultPipelinePath() : options.pipeline;
  Diagnostics diags;
  auto pipeline = loadPipeline(pipelinePath, diags);
  printDiagnostics(diags);
  if (!pipeline) return kExitFailure;
  // Render refuses what validate refuses, before any GL work: the graph at
  // this size (an explicit --max-texture-size included; the device's own
  // limit is checked when the executor compiles), the pass types' checks on
  // the config as written, and the shader checks (cached on disk). With a
  // config validate accepts, this prints nothing.
  if (options.checks) {
    CompileOptions compile = compileOptions(options.size.width, options.size.height, options.size.maxTextureSize);
    // Without --max-texture-size the device's own limit decides (the executor
    // checks it), not the OpenGL 4.5 minimum validate assumes.
    if (options.size.maxTextureSize == 0) compile.maxTextureSize = 0;
    Diagnostics checks;
    checkPipeline(*pipeline, compile, ShaderChecks::cached, checks, /*scenePresent=*/true);
    if (hasErrors(checks)) {
      printDiagnostics(checks);
      return kExitFailure;
    }
  }

  try {
    std::unique_ptr<Scene> scene;
    const std::string sceneSpec = options.scene.empty() ? std::string("learnopengl:overview") : options.scene;
    scene = std::make_unique<Scene>(loadSceneAny(sceneSpec));
    // Model no more than the scene needs (no point lights: no light volumes...).
    for (const auto& note : adaptToScene(*pipeline, PassRegistry::builtins(), sceneFeatures(*scene)).notes)
      spdlog::info("{}", note);

    ContextOptions ctxOptions;
    ctxOptions.window = options.window;
    ctxOptions.width = options.size.width;
    ctxOptions.height = options.size.height;
    auto context = GlContext::create(ctxOptions);
    spdlog::info("OpenGL {} on {}", context->version(), context->renderer());

    ShaderLibrary shaders;
    Executor executor(*pipeline, PassRegistry::builtins(), shaders, scene.get());
    executor.resize(Extent{options.size.width, options.size.height});

    std::vector<double> frameMs;
    std::map<std::string, std::vector<double>> passMs;
    std::vector<std::string> passOrder;
    const uint32_t frames = std::max<uint32_t>(1, options.frames);
    for (uint32_t i = 0; i < frames; ++i) {
      auto t0 = std::chrono::steady_clock::now();
      executor.renderFrame();
      auto t1 = std::chrono::steady_clock::now();
      frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      for (const auto& t : executor.timings()) {
        if (!passMs.count(t.name)) passOrder.push_back(t.name);
        passMs[t.name].push_back(t.ms);
      }
    }
    if (context->debugErrorCount() > 0)
      spdlog::warn("{} OpenGL errors were reported while rendering", context->debugErrorCount());

    const Extent extent = executor.outputExtent();
    writePng(options.out, extent.width, extent.height, executor.readOutputRGBA8());
    std::cout << "wrote " << options.out << " (" << extent.width << "x" << extent.height << ", " << frames
              << (frames == 1 ? " frame" : " frames") << ", median " << median(frameMs) << " ms)\n";
    if (!options.stats.empty()) writeStats(options.stats, frameMs, passMs, passOrder, executor.plan());
  } catch (const RuntimeError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace rgraph::cli
