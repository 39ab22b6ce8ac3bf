// The rgraph command line: validate, plan, dot, passes, render, check-hazards, bench. One
// function per subcommand sets up its options; main() parses and dispatches.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "cli_common.h"
#include "commands.h"

namespace {

using namespace rgraph::cli;

// Everything the command line sets; CLI11 writes into it while parsing.
struct Options {
  std::string logLevel = "warn";
  std::string pipeline;
  SizeOptions size;
  bool json = false;
  std::vector<std::string> pluginPaths;
  std::vector<std::string> shaderPaths;
  bool noShaders = false;                // validate
  std::string planScene;                 // plan
  PassesOptions passes;
  RenderOptions render;
  CheckHazardsOptions checkHazards;
  ViewOptions view;
  BenchOptions bench;
};

// ------------------------------------------------------------ shared options

// An empty value names nothing: refused rather than read as "not given" (an
// empty --scene once rendered the default scene).
const CLI::Validator kNotEmpty(
    [](const std::string& value) { return value.empty() ? "an empty value names nothing" : std::string(); }, "");

void addPluginPath(CLI::App* cmd, Options& o) {
  cmd->add_option("--plugin-path", o.pluginPaths,
                  "folder searched for plugins named by the config (repeatable; before $RGRAPH_PLUGIN_PATH)")
      ->type_name("DIR")
      ->check(kNotEmpty)
      ->allow_extra_args(false);
}

void addMaxTextureSize(CLI::App* cmd, uint32_t& target, const char* defaultText) {
  cmd->add_option("--max-texture-size", target,
                  std::string("largest texture width or height the pipeline may use (default: ") + defaultText + ")")
      ->type_name("N")
      ->check(CLI::Range(1u, 1u << 20));
}

void addSize(CLI::App* cmd, SizeOptions& size, const char* maxTextureDefault) {
  cmd->add_option("--width", size.width, "output width in pixels")->check(CLI::Range(1u, 16384u));
  cmd->add_option("--height", size.height, "output height in pixels")->check(CLI::Range(1u, 16384u));
  addMaxTextureSize(cmd, size.maxTextureSize, maxTextureDefault);
}
// render and view: the textures' budget (RendererOptions::maxMemoryBytes).
void addMaxMemory(CLI::App* cmd, SizeOptions& size) {
  cmd->add_option("--max-memory", size.maxMemoryBytes,
                  "refuse to build the pipeline at a size whose textures need more than this many bytes "
                  "(suffixes KB, MB, GB: powers of 1024; default: no budget but what the device says it has free)")
      ->type_name("BYTES")
      ->transform(CLI::AsSizeValue(false));
}
constexpr const char* kGlMinimum = "16384, what every OpenGL 4.5 device supports";

void addShaderPath(CLI::App* cmd, Options& o) {
  cmd->add_option("--shader-path", o.shaderPaths,
                  "folder of shaders, searched before the built-in ones (repeatable); shader names in a config "
                  "are read only from inside shader folders")
      ->type_name("DIR")
      ->check(kNotEmpty)
      ->allow_extra_args(false);
}

// ------------------------------------------------------------ subcommands

CLI::App* addValidate(CLI::App& app, Options& o) {
  auto* cmd = app.add_subcommand("validate", "check a pipeline config; exit 1 with diagnostics if invalid");
  cmd->add_option("pipeline", o.pipeline, "pipeline config (JSON)")->required()->check(kNotEmpty);
  cmd->add_flag("--json", o.json, "print diagnostics as a JSON array");
  cmd->add_flag("--no-shaders", o.noShaders, "skip the glslang shader checks");
  addSize(cmd, o.size, kGlMinimum);
  addPluginPath(cmd, o);
  addShaderPath(cmd, o);
  return cmd;
}

CLI::App* addPlan(CLI::App& app, Options& o) {
  auto* cmd = app.add_subcommand("plan", "print the compiled plan: order, culled passes, lifetimes, memory");
  cmd->add_option("pipeline", o.pipeline, "pipeline config (JSON)")->required()->check(kNotEmpty);
  cmd->add_flag("--json", o.json, "print the plan as JSON");
  cmd->add_option(
      "--scene", o.planScene,
      "adapt the pipeline to this scene first (drops what it does not need): file, glTF or procedural name")
      ->check(kNotEmpty);
  addSize(cmd, o.size, kGlMinimum);
  addPluginPath(cmd, o);
  return cmd;
}

CLI::App* addDot(CLI::App& app, Options& o) {
  auto* cmd = app.add_subcommand("dot", "print the compiled graph as graphviz DOT");
  cmd->add_option("pipeline", o.pipeline, "pipeline config (JSON)")->required()->check(kNotEmpty);
  addSize(cmd, o.size, kGlMinimum);
  addPluginPath(cmd, o);
  return cmd;
}

CLI::App* addPasses(CLI::App& app, Options& o) {
  auto* cmd = app.add_subcommand(
      "passes", "list the pass types: what each binds in inputs and outputs, its params and its rules");
  cmd->add_option("type", o.passes.types, "only these types (with --plugin: the plugin's types too)")
      ->type_name("TYPE");
  cmd->add_flag("--json", o.passes.json, "print as JSON");
  cmd->add_option("--plugin", o.passes.plugins,
                  "load this plugin (name or path; repeatable) and list only its types")
      ->type_name("NAME")
      ->allow_extra_args(false);
  addPluginPath(cmd, o);
  return cmd;
}

CLI::App* addRender(CLI::App& app, Options& o) {
  RenderOptions& r = o.render;
  auto* cmd = app.add_subcommand("render", "run a pipeline headless and write the output image");
  cmd->add_option("pipeline", r.pipeline, "pipeline config (default: pipelines/default.json)")->check(kNotEmpty);
  cmd->add_option("--out,-o", r.out, "output PNG")->required()->check(kNotEmpty);
  cmd->add_option(
      "--scene", r.scene,
      "scene file (.json), glTF (.gltf/.glb), learnopengl, learnopengl:overview (default), learnopengl:shadows, thin (thin edges that alias), walker (skinned figures walking) or many-lights:N[:seed][:pillars]")
      ->check(kNotEmpty);
  cmd->add_option("--frames", r.frames, "frames to render (timings are medians)")->check(CLI::Range(1u, 100000u));
  cmd->add_option_function<std::string>(
         "--cut", [&r](const std::string& v) { r.cuts = v; },
         "camera cuts before these frames (0-based, below --frames): history resources start again "
         "(cleared, invalid) and motion is zero there")
      ->type_name("K[,K...]");
  cmd->add_option_function<std::string>(
         "--orbit", [&r](const std::string& v) { r.orbit = v; },
         "turn the camera this many degrees per frame about its up axis through its target "
         "(frame i: i times that; negative: the other way, as --orbit=-D)")
      ->type_name("DEGREES");
  cmd->add_option_function<std::string>(
         "--time", [&r](const std::string& v) { r.time = v; },
         "the animation clock of the first frame (glTF animations, skins, morph targets; they loop)")
      ->type_name("SECONDS");
  cmd->add_option_function<std::string>(
         "--fps", [&r](const std::string& v) { r.fps = v; },
         "play the animation at this rate over --frames (frame i at --time + i / F; the last frame is written); "
         "without it every frame is at --time")
      ->type_name("F");
  cmd->add_option("--environment", r.environment,
                  "image-based lighting for the scene, over its own \"environment\": sky (the procedural sky), "
                  "color:R,G,B (uniform radiance) or an equirectangular .hdr file")
      ->type_name("sky|color:R,G,B|FILE.hdr")
      ->check(kNotEmpty);
  cmd->add_option("--stats", r.stats, "write frame and pass timings and memory as JSON")->check(kNotEmpty);
  cmd->add_option("--camera", r.camera,
                  "camera at px,py,pz looking at tx,ty,tz, optionally with a vertical field of view in degrees "
                  "(default: the scene's camera; near, far and up stay the scene's)")
      ->type_name("px,py,pz,tx,ty,tz[,fov]")
      ->check(kNotEmpty);
  cmd->add_flag("--window", r.window, "render in a GLFW window instead of headless EGL");
  cmd->add_flag("!--no-checks", r.checks,
                "skip what validate checks before rendering (graph, pass checks, glslang shader checks; "
                "their results are cached under $XDG_CACHE_HOME/rgraph)");
  cmd->add_option("--hazards", r.hazards,
                  "hazard modes (docs/testing.md): poison, no-alias, alias-shuffle, reorder[:K], state-scramble, "
                  "no-cull, comma-separated")
      ->type_name("MODE[,MODE]")
      ->check(kNotEmpty);
  addPluginPath(cmd, o);
  addSize(cmd, r.size, "the device's GL_MAX_TEXTURE_SIZE");
  addMaxMemory(cmd, r.size);
  addShaderPath(cmd, o);
  return cmd;
}

CLI::App* addCheckHazards(CLI::App& app, Options& o) {
  CheckHazardsOptions& c = o.checkHazards;
  auto* cmd = app.add_subcommand(
      "check-hazards",
      "render a pipeline plain and under each hazard mode and compare; exit 1 naming the first pass that differs");
  cmd->add_option("pipeline", c.pipeline, "pipeline config (default: pipelines/default.json)")->check(kNotEmpty);
  cmd->add_option("--scene", c.scene, "as render's --scene (default learnopengl:overview)")->check(kNotEmpty);
  cmd->add_option("--frames", c.frames, "frames per run (history is compared over them; default 3)")
      ->check(CLI::Range(1u, 1000u));
  cmd->add_option("--hazards", c.hazards, "the modes to run (default: all of them, reorder:3)")
      ->type_name("MODE[,MODE]")
      ->check(kNotEmpty);
  addPluginPath(cmd, o);
  addSize(cmd, c.size, "the device's GL_MAX_TEXTURE_SIZE");
  addShaderPath(cmd, o);
  return cmd;
}

CLI::App* addBench(CLI::App& app, Options& o) {
  BenchOptions& b = o.bench;
  auto* cmd = app.add_subcommand("bench",
                                 "sweep lighting methods, light counts, G-buffer layouts, cut-offs, "
                                 "resolutions and anti-aliasing methods; write results.csv, results.json, "
                                 "figures.md and charts");
  cmd->add_option("--out,-o", b.out, "output folder")->required()->check(kNotEmpty);
  cmd->add_flag("--quick", b.quick, "fewer points and frames (light counts up to 1,024, 640x360 mostly)");
  cmd->add_option("--scene", b.scene,
                  "scene of the lighting axes (default: many-lights, N swept); a file's first N lights. The aa "
                  "axis always uses learnopengl:overview, thin and walker")
      ->check(kNotEmpty);
  cmd->add_option("--only", b.only,
                  "run one axis only: lights (with lights_exact), lights_exact (the exact loop at each light count), "
                  "layout, layout_exact, threshold, resolution, pillars, aa (anti-aliasing against a 16-sample reference), "
                  "post (bloom and SSAO methods) or shadows (shadow methods against exact visibility)")
      ->type_name("AXIS");
  cmd->add_flag("--figures-only", b.figuresOnly,
                "render each point once, untimed: errors and bytes only (the figures docs quote), no charts");
  cmd->add_flag("--smoke", b.smoke, "tiny sweep for tests (2 points, 64x64, 1 frame)")->group("");
  cmd->add_option("--replot", b.replot,
                  "redraw the charts and figures.md of a previous run's results.json (no rendering)")
      ->type_name("JSON")
      ->check(kNotEmpty);
  return cmd;
}

CLI::App* addView(CLI::App& app, Options& o) {
  ViewOptions& v = o.view;
  auto* cmd =
      app.add_subcommand("view", "an interactive window: camera controls, panels, live reload (docs/viewer.md)");
  cmd->add_option("pipeline", v.pipeline, "pipeline config (default: pipelines/default.json)")->check(kNotEmpty);
  cmd->add_option("--scene", v.scene, "as render's --scene; a scene file is reloaded when it changes")
      ->check(kNotEmpty);
  cmd->add_option("--script", v.script,
                  "run these commands (camera, wait, waitfile, screenshot, ui, param, resize, quit)")
      ->check(kNotEmpty);
  cmd->add_option("--status", v.status, "append one JSON line per load or reload to this file")->check(kNotEmpty);
  cmd->add_option("--stats", v.stats, "write median frame times with the UI on and off (JSON) at exit")
      ->check(kNotEmpty);
  addSize(cmd, v.size, "the device's GL_MAX_TEXTURE_SIZE");
  addMaxMemory(cmd, v.size);
  addPluginPath(cmd, o);
  addShaderPath(cmd, o);
  return cmd;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rgraph: a render-graph framework for deferred shading on OpenGL 4.5"};
  app.set_version_flag("--version", std::string("rgraph ") + RGRAPH_VERSION);
  app.require_subcommand(1);
  Options o;
  app.add_option("--log-level", o.logLevel, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  CLI::App* validate = addValidate(app, o);
  CLI::App* plan = addPlan(app, o);
  CLI::App* dot = addDot(app, o);
  CLI::App* passes = addPasses(app, o);
  CLI::App* render = addRender(app, o);
  CLI::App* bench = addBench(app, o);
  CLI::App* checkHazards = addCheckHazards(app, o);
  CLI::App* view = addView(app, o);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end parsing with exit code 0: CLI11 prints them.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    // Every usage error exits 1 like any other error (not CLI11's 105, 106...).
    std::cerr << "error: " << e.what() << " (rgraph --help, or rgraph COMMAND --help, lists the options)\n";
    return kExitFailure;
  }
  // Log lines (the loaders' warnings among them) go to stderr: stdout carries
  // what a command prints (a plan, JSON), which a script may read.
  // (Unnamed, like spdlog's own default logger: the lines keep their form.)
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("", std::make_shared<spdlog::sinks::stderr_color_sink_mt>()));
  spdlog::set_level(spdlog::level::from_str(o.logLevel));

  if (!checkFolders("--plugin-path", o.pluginPaths) || !checkFolders("--shader-path", o.shaderPaths))
    return kExitFailure;
  for (const auto& dir : o.pluginPaths) addPluginSearchDirectory(dir);
  addShaderPaths(o.shaderPaths);

  try {
    if (*validate) return runValidate(o.pipeline, o.size, o.json, !o.noShaders);
    if (*plan) return runPlan(o.pipeline, o.size, o.json, o.planScene);
    if (*dot) return runDot(o.pipeline, o.size);
    if (*passes) return runPasses(o.passes);
    if (*render) return runRender(o.render);
    if (*bench) return runBench(o.bench);
    if (*checkHazards) return runCheckHazards(o.checkHazards);
    if (*view) return runView(o.view);
  } catch (const std::exception& e) {
    // Anything a user can cause is reported as a diagnostic or a RuntimeError
    // above; this is the last line of defence against a crash.
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitFailure;
}
