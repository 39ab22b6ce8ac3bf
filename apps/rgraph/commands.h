// One function per `rgraph` subcommand; each returns the process exit code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rgraph::cli {

struct SizeOptions {
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t maxTextureSize = 0;  // --max-texture-size; 0: not given (16384, or render: the device's)
  uint64_t maxMemoryBytes = 0;  // --max-memory (render, view): RendererOptions::maxMemoryBytes; 0: none
};

// checkShaders: after the graph compiles, compile and reflect every enabled
// pass's shaders with glslang (rgraph/shader_check.h); `--no-shaders` skips it.
int runValidate(const std::string& pipeline, const SizeOptions& size, bool json, bool checkShaders = true);
// scene: when set, the pipeline is first adapted to what the scene needs
// (PassTypeDesc::adapt) and the plan reports G-buffer bytes per pixel before and after.
int runPlan(const std::string& pipeline, const SizeOptions& size, bool json, const std::string& scene = {});
int runDot(const std::string& pipeline, const SizeOptions& size);

// `rgraph passes` (cmd_passes.cpp): the registered pass types, their slots,
// params and rules, as text or JSON.
struct PassesOptions {
  std::vector<std::string> types;    // only these (unknown: an error, exit 1)
  std::vector<std::string> plugins;  // --plugin: load these; list only their types unless `types` says
  bool json = false;
};
int runPasses(const PassesOptions& options);

struct RenderOptions {
  std::string pipeline;   // empty: the default pipeline
  std::string out;        // PNG path
  std::string scene;      // scene file, .gltf/.glb, or a procedural name
  std::string stats;      // stats JSON path (optional)
  std::string camera;     // "px,py,pz,tx,ty,tz[,fovDeg]"; empty: the scene's camera
  SizeOptions size;
  uint32_t frames = 1;
  // --cut "K[,K...]": camera cuts before these 0-based frames (checked by
  // render: a malformed or out-of-range value is an error, exit 1).
  std::optional<std::string> cuts;
  // --orbit DEGREES: the camera's turn about its target per frame (as given;
  // render checks it is a finite number).
  std::optional<std::string> orbit;
  // --time SECONDS and --fps F (as given; render checks them): the scene's
  // animation clock at the first frame, and its rate: frame i is at
  // time + i / fps (without --fps every frame is at --time).
  std::optional<std::string> time, fps;
  // --environment sky|color:R,G,B|FILE.hdr: image-based lighting for the
  // scene, over its own (a bare glTF has none).
  std::string environment;
  bool window = false;
  // false (--no-checks): skip the checks validate runs (graph, pass checks,
  // glslang shader checks, cached on disk) before any GL work.
  bool checks = true;
  // --hazards MODE[,MODE] (rgraph/hazards.h; render checks the list).
  std::string hazards;
};
int runRender(const RenderOptions& options);

// `rgraph check-hazards` (cmd_check_hazards.cpp): the pipeline plain and under
// each hazard mode, compared (rgraph/hazard_check.h); exit 1 on a finding.
struct CheckHazardsOptions {
  std::string pipeline;  // empty: the default pipeline
  std::string scene;     // as render's --scene
  uint32_t frames = 3;
  std::string hazards;   // empty: every mode (reorder:3)
  SizeOptions size{64, 64};
};
int runCheckHazards(const CheckHazardsOptions& options);

// `rgraph view` (view/view_main.cpp, docs/viewer.md): an interactive window with live reload.
struct ViewOptions {
  std::string pipeline;  // empty: the default pipeline
  std::string scene;     // as render's --scene
  std::string script;    // --script FILE: one command per line
  std::string status;    // --status FILE: one JSON line per load or reload
  std::string stats;     // --stats FILE: median frame times with the UI on and off
  SizeOptions size;
};
int runView(const ViewOptions& options);

// `rgraph bench`: sweeps lighting methods, light counts, G-buffer layouts,
// cut-off thresholds and resolutions, and anti-aliasing methods (the aa axis); writes results.csv, results.json and
// figures.md and charts (SVG + PNG) under `out` (cmd_bench.cpp, bench.h).
struct BenchOptions {
  std::string out;     // output folder (created)
  std::string scene;   // empty: many-lights (the light-count axis varies N)
  bool quick = false;  // fewer points and frames: under 3 minutes of CPU on 2 cores with llvmpipe
  bool smoke = false;  // hidden: 2 points at 64x64, 1 frame each (tests)
  bool figuresOnly = false;  // one untimed frame per point: the deterministic figures only, no charts
  std::string replot;  // a previous run's results.json: redraw its charts under `out`, render nothing
  std::string only;    // non-empty: run only the rows of this axis (lights, layout, ..., aa)
};
int runBench(const BenchOptions& options);

}  // namespace rgraph::cli
