// Internal to `rgraph bench` (cmd_bench.cpp runs it): what a sweep point is
// (bench_sweep.cpp: configurations, their pipelines, the scenes), how one is
// rendered and measured (bench_measure.cpp), and how results are written
// (bench_report.cpp: CSV, JSON, checks, the figure tables the docs quote;
// bench_plots.cpp: the charts).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "median.h"
#include "rgraph/config.h"
#include "rgraph/graph.h"
#include "rgraph/scene.h"

namespace rgraph {
class Executor;
class GlContext;
class ShaderLibrary;
}  // namespace rgraph

namespace rgraph::cli::bench {

// ---------------------------------------------------------------- what is swept

extern const std::vector<std::string> kMethods;  // forward_lit, fullscreen, fullscreen_radius, light_volumes, tiled, tiled_far, clustered, clustered_far
extern const std::vector<std::string> kLayouts;  // pbr, learnopengl, compact, fp32
constexpr double kDefaultThreshold = 5.0 / 256.0;

struct Config {
  std::string method = "light_volumes";
  std::string layout = "pbr";  // unused by forward_lit
  double threshold = kDefaultThreshold;
  int lights = 256;
  Extent size{640, 360};
  // The many-lights:N:pillars scene (axis "pillars": depth discontinuities,
  // tiles against clusters) instead of the sweep's scene.
  bool pillars = false;

  bool deferred() const { return method != "forward_lit"; }
  std::string key() const;  // equal keys: the same configuration
};

std::string methodTitle(const std::string& method);
std::string thresholdText(double threshold);  // "5/256", "none"
std::string sizeText(Extent e);               // "640x360"
std::string describe(const Config& c);        // one line for progress and messages

// The pipeline of a point as config JSON. reference: forward_lit with no
// cut-off into an rgba32f HDR target (no G-buffer quantisation at all).
std::string pipelineJson(const Config& c, bool reference);
// Parses and builds a generated pipeline; errors throw (they are bugs here).
PipelineConfig buildPipeline(const std::string& text, const std::string& name);

// The scenes of a sweep: the procedural many-lights scene at each light
// count, or a scene file with its first N point lights.
class Scenes {
 public:
  explicit Scenes(const std::string& spec);
  ~Scenes();
  bool procedural() const { return procedural_; }
  int defaultLights() const { return defaultLights_; }
  const std::string& spec() const { return spec_; }
  std::vector<int> lightCounts(bool quick) const;
  const Scene& get(int lights, bool pillars = false);  // built once per count (pillars: procedural only)

 private:
  std::string spec_;
  bool procedural_ = false;
  int defaultLights_ = 256;
  uint32_t seed_ = 1;
  std::unique_ptr<Scene> base_;
  std::map<std::pair<int, bool>, std::unique_ptr<Scene>> cache_;
};

// ---------------------------------------------------------------- measuring one point

struct FrameBudget {
  int warm = 2;            // untimed frames first
  int minFrames = 3;       // timed frames, at least
  int maxFrames = 5;       // and at most
  double budgetMs = 1500;  // timed frames are cut to fit this
  // A first frame longer than this (ms; 0: never) is the only one: its time,
  // shader compilation included, is the point's (the full sweep's every-light
  // loops at 10,000 lights take tens of seconds a frame, compilation well
  // under one).
  double singleFrameMs = 0;
};

struct Measured {
  std::vector<uint8_t> image;
  std::vector<double> frameMs;
  std::vector<std::string> passOrder;
  std::map<std::string, std::vector<double>> passMs;
  uint32_t gbufferBytes = 0, gbufferBytesAdapted = 0;
  uint64_t allocatedBytes = 0, naiveBytes = 0;
  uint64_t glErrors = 0;
  double wallMs = 0;  // everything: build, compile, warm-up, frames, read-back
};

struct ImageError {
  double psnr = 0;   // dB over RGB, capped at kPsnrCap (identical or nearly)
  int maxAbs = 0;    // 8-bit
  double over1 = 0;  // share of pixels with a channel off by more than 1/255
  double over2 = 0;  // and by more than 2/255
};
constexpr double kPsnrCap = 100.0;

using cli::median;  // median.h
// Builds the pipeline, adapts it to the scene as `rgraph render` does, renders
// warm-up and timed frames within the budget, reads the output back.
Measured measure(const std::string& pipelineText, const std::string& name, const Scene& scene, Extent size,
                 ShaderLibrary& shaders, GlContext& context, const FrameBudget& budget);
Measured measure(PipelineConfig pipeline, const Scene& scene, Extent size, ShaderLibrary& shaders, GlContext& context,
                 const FrameBudget& budget);
// The executor measure() renders with: `cfg` adapted to the scene as
// `rgraph render` does, built and sized. Throws RuntimeError.
std::unique_ptr<Executor> makeExecutor(PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders);
// One frame, wall clock around renderFrame() + glFinish(), in ms. The
// finish puts that frame's timer query results in: exec.timings() are then
// its own (Executor::collectTimings) whenever timedPasses(exec) says so.
double timedFrame(Executor& exec);
// Whether exec.timings() are of the frame just rendered (the only pass times
// a bench records: GPU queries are otherwise of an earlier frame).
bool timedPasses(const Executor& exec);
ImageError compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& ref);
// A rough cost model (ms at 640x360 on llvmpipe), for the ETA only.
double estimateFrameMs(const Config& c);

// ---------------------------------------------------------------- shipped pipelines

// The shipped LearnOpenGL-family pipelines, each against pipelines/forward.json
// on the bench's default scene and size: how far the methods agree as shipped
// (bench/render_methods.cpp times the same pipelines side by side).
struct ShippedMethod {
  const char* name;
  const char* file;  // under pipelines/ The shipped deferred pipelines keep LearnOpenGL's rgba16f position
  // target; the variant stores position in rgba32f, so that only the
  // lighting method differs from forward shading.
  bool fp32Position = false;
  // deferred-blinn-phong.json ships with no cut-off (LearnOpenGL 8.1): this
  // pass gets the others' 5/256 so that only the method differs.
  const char* cutOffPass = nullptr;
};
extern const std::vector<ShippedMethod> kShippedMethods;
void applyShippedVariant(const ShippedMethod& m, PipelineConfig& cfg);

struct ShippedResult {
  ShippedMethod method;
  ImageError err;     // against forward.json
  std::string error;  // non-empty: it failed to run
};
std::vector<ShippedResult> measureShipped(const std::string& pipelineDir, const Scene& scene, Extent size,
                                          ShaderLibrary& shaders, GlContext& context);

// ---------------------------------------------------------------- the sweep

struct Point {
  Config cfg;
  std::vector<std::string> axes;
  Measured m;
  ImageError err;
  // Against the exact loop at the same light count and size (exactConfig()),
  // where the sweep has it: what a method loses to the cut-off and to its
  // G-buffer, measured from the image users compare with.
  ImageError errExact;
  bool hasExact = false;
  std::string error;  // non-empty: the point failed (message)
  bool ok() const { return error.empty(); }
};

// The exact loop at c's light count and size: the fullscreen method, no
// cut-off, the default layout (axis "lights_exact": the reference time and
// image at each N).
Config exactConfig(const Config& c, const Config& def);

// One axis at a time around `def`, plus the method x light-count grid (and,
// on a procedural scene, tiled against clustered on its pillars variant);
// each configuration once, with every axis it belongs to; cheap points first.
std::vector<Point> planSweep(const Config& def, const Scenes& scenes, bool quick, bool smoke);
// Fills errExact/hasExact of every point whose exact loop (exactConfig) is in
// `points` with an image, from the points' images (Measured::image).
void compareWithExact(std::vector<Point>& points, const Config& def);

// ---------------------------------------------------------------- the aa axis

// Anti-aliasing methods (bench_aa.cpp) on scenes with edges that alias,
// against a 16-sample reference: the method's own pipeline at 4x the width
// and height, jitter off, one frame after a camera cut, box-filtered 4x4
// down in its stored 8-bit values (bench_aa_metrics.h).
struct AaPlan {
  Extent size{640, 360};
  int warm = 2;            // untimed frames first (non-temporal methods)
  int timedFrames = 5;     // non-temporal methods
  int taaFrames = 32;      // static camera: frames before the image is read (all timed)
  int orbitWarm = 8;       // orbit and moving: frames before the first scored one
  int orbitFrames = 16;    // orbit and moving: scored frames (each against its own reference)
  float orbitDegrees = 1;  // orbit: camera turn per frame about the target's vertical axis (moving: the
                           // objects' turn, the other way)
  double walkFps = 30;     // walk: the animation clock advances 1/walkFps seconds per frame
};
AaPlan aaPlan(bool quick);

struct AaRow {
  std::string scene;     // loadSceneAny spec
  std::string aa;        // none, fxaa, taa, taa_orbit, msaa4, none_moving, taa_moving, none_walk, taa_walk
  std::string pipeline;  // file under pipelines/
  Extent size;
  int frames = 0;  // rendered before (the last) image was read
  std::vector<double> frameMs;
  double psnr = 0.0, edgePsnr = 0.0;  // dB (orbit and moving rows: mean over scored frames)
  size_t edgePixels = 0;              // of the reference (orbit and moving rows: mean)
  int maxAbs = 0;                     // 8-bit (orbit and moving rows: over scored frames)
  std::string error;                  // non-empty: the row failed (message)
  bool ok() const { return error.empty(); }
};
extern const std::vector<std::string> kAaScenes;  // learnopengl:overview, thin, walker
std::vector<AaRow> planAa(const AaPlan& plan);
// Renders every row; returns the number that failed. timed false: no frame
// times kept (--figures-only); the images are the same either way.
size_t runAa(std::vector<AaRow>& rows, const AaPlan& plan, const std::string& pipelineDir, ShaderLibrary& shaders,
             bool timed);
nlohmann::json aaJson(const AaRow& r);
AaRow aaFromJson(const nlohmann::json& j);
// The chart aa_ms_vs_error (figureTables() gives the rows' table "aa").
void drawAaChart(const std::string& dir, const std::vector<AaRow>& rows, const std::string& machine);

// ---------------------------------------------------------------- results

// Sweep points, then aa rows (their own columns scene, aa, edge_psnr_db, edge_pixels; empty on points), then
// shadows rows (bench_shadows.h; their own columns map_size, cascades, shadow_ms, atlas_bytes).
struct ShadowRow;
void writeCsv(const std::string& path, const std::vector<Point>& points, const std::vector<AaRow>& aa,
              const std::vector<ShadowRow>& shadows);
nlohmann::json pointJson(const Point& p);
Point pointFromJson(const nlohmann::json& j, const Config& def);
Config defaultPointFromJson(const nlohmann::json& results);
nlohmann::json shippedJson(const ShippedResult& r);
ShippedResult shippedFromJson(const nlohmann::json& j);  // name and figures (enough for the tables)

// The headline comparisons (results.json "checks") and one summary line each.
nlohmann::json headlineChecks(const std::vector<Point>& points, const Config& def, std::vector<std::string>& summary);

// Markdown tables of the deterministic figures (PSNR, max error, share off,
// bytes per pixel, allocated/naive texture bytes), the blocks docs quote
// between `<!-- bench-figures:NAME -->` markers. name -> table text.
std::map<std::string, std::string> figureTables(const std::vector<Point>& points, const Config& def,
                                                const std::vector<ShippedResult>& shipped,
                                                const std::vector<AaRow>& aa);

void drawCharts(const std::string& dir, const std::vector<Point>& points, const Config& def, const std::string& machine,
                const std::string& sceneText);
std::string sceneNote(const std::string& spec, bool procedural);

}  // namespace rgraph::cli::bench
