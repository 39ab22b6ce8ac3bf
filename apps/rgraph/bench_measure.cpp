// `rgraph bench`, measuring one point: build its pipeline, adapt it to the
// scene as `rgraph render` does, time frames, read the image back, and
// compare images.
//
// Timing: wall clock around Executor::renderFrame() + glFinish(), after
// warm-up frames (shader compiles, first-touch allocations). On llvmpipe GL
// timer queries are wrong (see PLATFORM notes), so this is the only clock.
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/image.h"
#include "rgraph/registry.h"

namespace rgraph::cli::bench {

using Clock = std::chrono::steady_clock;

Measured measure(const std::string& pipelineText, const std::string& name, const Scene& scene, Extent size,
                 ShaderLibrary& shaders, GlContext& context, const FrameBudget& budget) {
  return measure(buildPipeline(pipelineText, name), scene, size, shaders, context, budget);
}

std::unique_ptr<Executor> makeExecutor(PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders) {
  const float aspect = size.height > 0 ? float(size.width) / float(size.height) : 16.0f / 9.0f;
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene, scene.camera, aspect));  // as `rgraph render` does
  auto exec = std::make_unique<Executor>(cfg, processRegistry(), shaders, &scene);
  exec->resize(size);
  return exec;
}

double timedFrame(Executor& exec) {
  const auto t0 = Clock::now();
  exec.renderFrame();
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  exec.collectTimings();  // after the finish: in, no wait
  return ms;
}

bool timedPasses(const Executor& exec) { return exec.frameIndex() > 0 && exec.timingsFrame() == exec.frameIndex() - 1; }

Measured measure(PipelineConfig cfg, const Scene& scene, Extent size, ShaderLibrary& shaders, GlContext& context,
                 const FrameBudget& budget) {
  const auto start = Clock::now();
  Measured m;
  {
    CompileOptions opts;
    opts.output = size;
    const Plan declared = compile(cfg.graph, opts);
    m.gbufferBytes = gbufferBytesPerPixel(cfg, declared, processRegistry());
  }
  const uint64_t errorsBefore = context.debugErrorCount();
  const std::unique_ptr<Executor> owned = makeExecutor(cfg, scene, size, shaders);
  Executor& exec = *owned;
  m.gbufferBytesAdapted = gbufferBytesPerPixel(cfg, exec.plan(), processRegistry());
  m.allocatedBytes = exec.plan().allocatedBytes;
  m.naiveBytes = exec.plan().naiveBytes;

  auto frame = [&]() { return timedFrame(exec); };
  auto keep = [&](double ms) {
    m.frameMs.push_back(ms);
    if (!timedPasses(exec)) return;
    for (const auto& t : exec.timings()) {
      if (!m.passMs.count(t.name)) m.passOrder.push_back(t.name);
      m.passMs[t.name].push_back(t.ms);
    }
  };
  int target = budget.maxFrames;
  for (int i = 0; i < budget.warm; ++i) {
    // The first frame compiles shaders; a dear point needs no second warm-up,
    // and a very dear one no other frame.
    const double ms = frame();
    if (i == 0 && budget.singleFrameMs > 0 && ms > budget.singleFrameMs) {
      keep(ms);
      target = 0;
      break;
    }
    if (ms > budget.budgetMs / 3) break;
  }
  for (int i = 0; i < target; ++i) {
    const double ms = frame();
    keep(ms);
    if (i == 0) {  // the first timed frame sets how many fit the budget
      const int fit = static_cast<int>(budget.budgetMs / std::max(ms, 1e-3));
      target = std::clamp(fit, budget.minFrames, budget.maxFrames);
    }
  }
  m.image = exec.readOutputRGBA8();
  m.glErrors = context.debugErrorCount() - errorsBefore;
  m.wallMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return m;
}

ImageError compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& ref) {
  if (a.size() != ref.size() || a.empty()) return {0.0, 255, 1.0, 1.0};
  const ImageDifference d = compareRGBA8(a, ref);
  return {d.psnr(kPsnrCap), d.maxAbs, d.shareOver(1), d.shareOver(2)};
}

// A rough model of a point's cost (ms, 640x360 on llvmpipe with 2 threads),
// for the ETA only: the sweep grows from cheap to dear points.
double estimateFrameMs(const Config& c) {
  const double px = double(c.size.width) * c.size.height / (640.0 * 360.0);
  const double n = c.lights;
  double ms = 0;
  if (c.method == "forward_lit")
    ms = 10 + 0.5 * n;
  else if (c.method == "fullscreen")
    ms = 15 + 0.38 * n;
  else if (c.method == "fullscreen_radius")
    ms = 15 + 0.3 * n;
  else if (c.method == "light_volumes")
    ms = 20 + 0.06 * n;
  else
    ms = 20 + 0.05 * n;
  return ms * px;
}

// ---------------------------------------------------------------- shipped pipelines

namespace {
PipelineConfig loadShipped(const std::string& path) { return loadPipelineFileOrThrow(path); }
}  // namespace

std::vector<ShippedResult> measureShipped(const std::string& pipelineDir, const Scene& scene, Extent size,
                                          ShaderLibrary& shaders, GlContext& context) {
  const FrameBudget once{0, 1, 1, 0};
  const std::vector<uint8_t> forward =
      measure(loadShipped(pipelineDir + "/forward.json"), scene, size, shaders, context, once).image;
  std::vector<ShippedResult> out;
  for (const ShippedMethod& m : kShippedMethods) {
    ShippedResult r{m, {}, {}};
    try {
      PipelineConfig cfg = loadShipped(pipelineDir + "/" + m.file);
      applyShippedVariant(m, cfg);
      r.err = compareImages(measure(std::move(cfg), scene, size, shaders, context, once).image, forward);
    } catch (const RuntimeError& e) {
      r.error = e.what();
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace rgraph::cli::bench
