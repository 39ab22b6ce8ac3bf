// The rgraph command line: validate, plan, dot, passes, render.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "cli_common.h"
#include "commands.h"

int main(int argc, char** argv) {
  using namespace rgraph::cli;
  CLI::App app{"rgraph: a render-graph framework for deferred shading on OpenGL 4.5"};
  app.set_version_flag("--version", std::string("rgraph ") + RGRAPH_VERSION);
  app.require_subcommand(1);
  std::string logLevel = "warn";
  app.add_option("--log-level", logLevel, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));

  std::string pipeline;
  SizeOptions size;
  bool json = false;
  std::vector<std::string> pluginPaths;
  auto addPluginPath = [&](CLI::App* cmd) {
    cmd->add_option("--plugin-path", pluginPaths,
                    "folder searched for plugins named by the config (repeatable; before $RGRAPH_PLUGIN_PATH)")
        ->type_name("DIR")
        ->allow_extra_args(false);
  };
  auto addMaxTextureSize = [](CLI::App* cmd, uint32_t& target, const char* defaultText) {
    cmd->add_option("--max-texture-size", target,
                    std::string("largest texture width or height the pipeline may use (default: ") + defaultText + ")")
        ->type_name("N")
        ->check(CLI::Range(1u, 1u << 20));
  };
  auto addSize = [&](CLI::App* cmd) {
    cmd->add_option("--width", size.width, "output width in pixels")->check(CLI::Range(1u, 16384u));
    cmd->add_option("--height", size.height, "output height in pixels")->check(CLI::Range(1u, 16384u));
    addMaxTextureSize(cmd, size.maxTextureSize, "16384, what every OpenGL 4.5 device supports");
  };
  std::vector<std::string> shaderPaths;
  auto addShaderPath = [&](CLI::App* cmd) {
    cmd->add_option("--shader-path", shaderPaths,
                    "folder of shaders, searched before the built-in ones (repeatable); shader names in a config "
                    "are read only from inside shader folders")
        ->type_name("DIR")
        ->allow_extra_args(false);
  };

  auto* validate = app.add_subcommand("validate", "check a pipeline config; exit 1 with diagnostics if invalid");
  validate->add_option("pipeline", pipeline, "pipeline config (JSON)")->required();
  validate->add_flag("--json", json, "print diagnostics as a JSON array");
  bool noShaders = false;
  validate->add_flag("--no-shaders", noShaders, "skip the glslang shader checks");
  addSize(validate);
  addPluginPath(validate);
  addShaderPath(validate);

  auto* plan = app.add_subcommand("plan", "print the compiled plan: order, culled passes, lifetimes, memory");
  plan->add_option("pipeline", pipeline, "pipeline config (JSON)")->required();
  plan->add_flag("--json", json, "print the plan as JSON");
  std::string planScene;
  plan->add_option(
      "--scene", planScene,
      "adapt the pipeline to this scene first (drops what it does not need): file, glTF or procedural name");
  addSize(plan);
  addPluginPath(plan);

  auto* dot = app.add_subcommand("dot", "print the compiled graph as graphviz DOT");
  dot->add_option("pipeline", pipeline, "pipeline config (JSON)")->required();
  addSize(dot);
  addPluginPath(dot);

  auto* passes = app.add_subcommand("passes", "list every registered pass type with its slots and parameters");
  passes->add_flag("--json", json, "print as JSON");
  std::vector<std::string> passPlugins;
  passes->add_option("--plugin", passPlugins, "also load this plugin (name or path; repeatable) and list its types")
      ->type_name("NAME")
      ->allow_extra_args(false);
  addPluginPath(passes);

  RenderOptions render;
  auto* renderCmd = app.add_subcommand("render", "run a pipeline headless and write the output image");
  renderCmd->add_option("pipeline", render.pipeline, "pipeline config (default: pipelines/default.json)");
  renderCmd->add_option("--out,-o", render.out, "output PNG")->required();
  renderCmd->add_option(
      "--scene", render.scene,
      "scene file (.json), glTF (.gltf/.glb), learnopengl, learnopengl:overview (default) or many-lights:N");
  renderCmd->add_option("--frames", render.frames, "frames to render (timings are medians)")
      ->check(CLI::Range(1u, 100000u));
  renderCmd->add_option("--stats", render.stats, "write frame and pass timings and memory as JSON");
  renderCmd->add_flag("--window", render.window, "render in a GLFW window instead of headless EGL");
  renderCmd->add_flag("!--no-checks", render.checks,
                      "skip what validate checks before rendering (graph, pass checks, glslang shader checks; "
                      "their results are cached under $XDG_CACHE_HOME/rgraph)");
  addPluginPath(renderCmd);
  renderCmd->add_option("--width", render.size.width, "output width in pixels")->check(CLI::Range(1u, 16384u));
  renderCmd->add_option("--height", render.size.height, "output height in pixels")->check(CLI::Range(1u, 16384u));
  addMaxTextureSize(renderCmd, render.size.maxTextureSize, "the device's GL_MAX_TEXTURE_SIZE");
  addShaderPath(renderCmd);

  BenchOptions bench;
  auto* benchCmd = app.add_subcommand("bench",
                                      "sweep lighting methods, light counts, G-buffer layouts, cut-offs and "
                                      "resolutions; write results.csv, results.json, figures.md and charts");
  benchCmd->add_option("--out,-o", bench.out, "output folder")->required();
  benchCmd->add_flag("--quick", bench.quick, "fewer points and frames (light counts up to 1,024, 640x360 mostly)");
  benchCmd->add_option("--scene", bench.scene, "scene (default: many-lights, N swept); a file's first N lights");
  benchCmd->add_flag("--figures-only", bench.figuresOnly,
                     "render each point once, untimed: errors and bytes only (the figures docs quote), no charts");
  benchCmd->add_flag("--smoke", bench.smoke, "tiny sweep for tests (2 points, 64x64, 1 frame)")->group("");
  benchCmd
      ->add_option("--replot", bench.replot,
                   "redraw the charts and figures.md of a previous run's results.json (no rendering)")
      ->type_name("JSON");

  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(logLevel));
  spdlog::set_default_logger(spdlog::default_logger());

  for (const auto& dir : pluginPaths) addPluginSearchDirectory(dir);
  if (!addShaderPaths(shaderPaths)) return kExitFailure;

  try {
    if (*passes && !loadPlugins(passPlugins)) return kExitFailure;
    if (*validate) return runValidate(pipeline, size, json, !noShaders);
    if (*plan) return runPlan(pipeline, size, json, planScene);
    if (*dot) return runDot(pipeline, size);
    if (*passes) return runPasses(json);
    if (*renderCmd) return runRender(render);
    if (*benchCmd) return runBench(bench);
  } catch (const std::exception& e) {
    // Anything a user can cause is reported as a diagnostic or a RuntimeError
    // above; this is the last line of defence against a crash.
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitFailure;
}
