// `rgraph bench`, the aa axis: anti-aliasing methods (none, FXAA, TAA
// converged on a still camera, during an orbit, with moving objects and on
// skinned figures walking, 4x MSAA forward) on scenes whose edges alias,
// each against a 16-sample reference of its own pipeline
// (bench.h: AaPlan, AaRow; the maths in bench_aa_metrics.h). Rows carry the
// axis name "aa" in the CSV's axes column.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "bench.h"
#include "bench_aa_metrics.h"
#include "bench_chart.h"
#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/image.h"
#include "rgraph/pipeline_load.h"

namespace rgraph::cli::bench {

using nlohmann::json;

const std::vector<std::string> kAaScenes = {"learnopengl:overview", "thin", "walker"};

namespace {

// still: a still camera; converged: TAA's history filled on a still camera;
// orbit: the camera turns about its target; moving: the camera and lights
// stay, every object turns about the target's vertical axis (a turntable):
// motion vectors from the objects' previous transforms, not the camera's;
// walk: the camera and lights stay, the scene's animation plays at
// AaPlan::walkFps (skinned figures: motion vectors from the previous pose).
enum class AaKind { still, converged, orbit, moving, walk };
// Which scenes a method runs on: the static ones (overview, thin), the
// animated one (walker) or both.
enum AaScenes : unsigned { kStaticScenes = 1, kAnimatedScenes = 2, kBothScenes = 3 };
struct AaMethod {
  const char* aa;
  const char* file;  // under pipelines/
  AaKind kind;
  unsigned scenes;
};
const AaMethod kAaMethods[] = {
    {"none", "default.json", AaKind::still, kBothScenes},
    {"none_orbit", "default.json", AaKind::orbit, kBothScenes},
    {"fxaa", "deferred-fxaa.json", AaKind::still, kStaticScenes},
    {"taa", "deferred-taa.json", AaKind::converged, kBothScenes},
    {"taa_orbit", "deferred-taa.json", AaKind::orbit, kBothScenes},
    {"msaa4", "forward-msaa.json", AaKind::still, kStaticScenes},
    {"none_moving", "default.json", AaKind::moving, kStaticScenes},
    {"taa_moving", "deferred-taa.json", AaKind::moving, kStaticScenes},
    {"none_walk", "default.json", AaKind::walk, kAnimatedScenes},
    {"taa_walk", "deferred-taa.json", AaKind::walk, kAnimatedScenes}};
bool animatedScene(const std::string& scene) { return scene == "walker"; }
constexpr int kReferenceFactor = 4;  // 4x4 = 16 samples per pixel

const AaMethod& methodOf(const AaRow& r) {
  for (const AaMethod& m : kAaMethods)
    if (r.aa == m.aa) return m;
  throw RuntimeError("bench: unknown aa method '" + r.aa + "'");
}

// Accumulates the per-frame errors of one row (one frame, or the orbit's mean).
struct ErrorSum {
  double psnr = 0, edgePsnr = 0, edgePixels = 0;
  int maxAbs = 0, n = 0;
  void add(const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference, Extent size) {
    const AaError e = aaError(image, reference, int(size.width), int(size.height), kPsnrCap);
    if (std::isnan(e.edgePsnr))
      throw RuntimeError("the reference has no edge pixels (luma step of " + std::to_string(kEdgeThreshold) +
                         "/255 between neighbours)");
    psnr += e.psnr;
    edgePsnr += e.edgePsnr;
    edgePixels += double(e.edgePixels);
    maxAbs = std::max(maxAbs, compareImages(image, reference).maxAbs);
    ++n;
  }
  void into(AaRow& r) const {
    r.psnr = psnr / n;
    r.edgePsnr = edgePsnr / n;
    r.edgePixels = size_t(std::lround(edgePixels / n));
    r.maxAbs = maxAbs;
  }
};

// $RGRAPH_BENCH_AA_IMAGES=DIR: each row's (last scored) image and its
// reference as PNGs, to look at what the figures measure.
void dumpImages(const AaRow& row, const std::vector<uint8_t>& image, const std::vector<uint8_t>& reference) {
  const char* dir = std::getenv("RGRAPH_BENCH_AA_IMAGES");
  if (!dir || !*dir) return;
  std::string name = row.scene + "_" + row.aa;
  std::replace(name.begin(), name.end(), ':', '-');
  std::filesystem::create_directories(dir);
  writePng((std::filesystem::path(dir) / (name + ".png")).string(), row.size.width, row.size.height, image);
  writePng((std::filesystem::path(dir) / (name + "_reference.png")).string(), row.size.width, row.size.height,
           reference);
}

// `rest` with every object turned by `degrees` about the vertical axis
// through `pivot` (bounds follow: culling and sorting read them).
void turnObjects(Scene& moved, const Scene& rest, const glm::vec3& pivot, float degrees) {
  const glm::mat4 one(1.0f);
  const glm::mat4 turn = glm::translate(one, pivot) * glm::rotate(one, glm::radians(degrees), {0.0f, 1.0f, 0.0f}) *
                         glm::translate(one, -pivot);
  for (size_t k = 0; k < moved.primitives.size(); ++k) {
    Primitive& p = moved.primitives[k];
    p.transform = turn * rest.primitives[k].transform;
    p.bounds = p.worldBounds(rest.meshes[static_cast<size_t>(p.mesh)].bounds);
  }
}

void runRow(AaRow& row, const AaPlan& plan, const Scene& rest, const std::string& pipelineDir,
            ShaderLibrary& shaders) {
  const AaMethod& method = methodOf(row);
  // Both executors draw `scene`: a moving row's objects are edited in this
  // copy between frames (executors read transforms from the scene each frame).
  Scene scene = rest;
  const PipelineConfig loaded = loadPipelineFileOrThrow((std::filesystem::path(pipelineDir) / row.pipeline).string());
  PipelineConfig cfg = loaded, refCfg = loaded;
  refCfg.jitterPhases = 0;  // the reference: no jitter error
  const std::unique_ptr<Executor> exec = makeExecutor(cfg, scene, row.size, shaders);
  const Extent big{row.size.width * kReferenceFactor, row.size.height * kReferenceFactor};
  const std::unique_ptr<Executor> ref = makeExecutor(refCfg, scene, big, shaders);
  // An animated scene is drawn posed (its animations all playing, as
  // `rgraph render --time` does): walk rows at frame i / walkFps, the others
  // at its clock's start, both executors alike.
  Pose pose;
  PosedBounds posed;
  auto poseAt = [&](double seconds) {
    if (scene.animation.empty()) return;
    evaluatePose(scene.animation, seconds, kAllAnimations, pose);
    poseScene(scene, pose, posed);
    for (Executor* e : {exec.get(), ref.get()})
      if (GpuScene* g = e->gpuScene()) g->setPose(pose.joints, pose.weights);
  };
  poseAt(0.0);
  auto reference = [&](const Camera& camera) {
    ref->setCamera(camera);
    ref->cameraCut();  // a temporal pipeline shows this frame alone
    ref->renderFrame();
    return boxDownsample(ref->readOutputRGBA8(), int(row.size.width), int(row.size.height), kReferenceFactor);
  };
  ErrorSum sum;
  exec->setCamera(scene.camera);
  if (method.kind == AaKind::orbit || method.kind == AaKind::moving || method.kind == AaKind::walk) {
    for (int i = 0; i < plan.orbitWarm + plan.orbitFrames; ++i) {
      Camera camera = scene.camera;
      if (method.kind == AaKind::orbit)
        camera = rgraph::orbitCamera(scene.camera, plan.orbitDegrees * float(i));  // as render --orbit
      else if (method.kind == AaKind::moving)
        turnObjects(scene, rest, scene.camera.target, -plan.orbitDegrees * float(i));
      else
        poseAt(double(i) / plan.walkFps);
      exec->setCamera(camera);
      const double ms = timedFrame(*exec);
      if (i >= plan.warm) row.frameMs.push_back(ms);
      if (i >= plan.orbitWarm) {
        const std::vector<uint8_t> image = exec->readOutputRGBA8(), expected = reference(camera);
        sum.add(image, expected, row.size);
        if (i + 1 == plan.orbitWarm + plan.orbitFrames) dumpImages(row, image, expected);
      }
    }
    row.frames = plan.orbitWarm + plan.orbitFrames;
  } else {
    // still: warm-up, then timed frames; converged: every frame counts
    // towards the history, the first ones are not timed (shader compiles).
    const int frames = method.kind == AaKind::converged ? plan.taaFrames : plan.warm + plan.timedFrames;
    for (int i = 0; i < frames; ++i) {
      const double ms = timedFrame(*exec);
      if (i >= plan.warm) row.frameMs.push_back(ms);
    }
    row.frames = frames;
    const std::vector<uint8_t> image = exec->readOutputRGBA8(), expected = reference(scene.camera);
    sum.add(image, expected, row.size);
    dumpImages(row, image, expected);
  }
  sum.into(row);
}

}  // namespace

AaPlan aaPlan(bool quick) {
  AaPlan p;
  if (quick) {  // the same images for the still methods; fewer timed and orbit frames
    p.timedFrames = 3;
    p.orbitFrames = 6;
  }
  return p;
}

std::vector<AaRow> planAa(const AaPlan& plan) {
  std::vector<AaRow> rows;
  for (const auto& scene : kAaScenes)
    for (const AaMethod& m : kAaMethods) {
      if (!(m.scenes & (animatedScene(scene) ? kAnimatedScenes : kStaticScenes))) continue;
      AaRow r;
      r.scene = scene;
      r.aa = m.aa;
      r.pipeline = m.file;
      r.size = plan.size;
      rows.push_back(std::move(r));
    }
  return rows;
}

size_t runAa(std::vector<AaRow>& rows, const AaPlan& plan, const std::string& pipelineDir, ShaderLibrary& shaders,
             bool timed) {
  std::map<std::string, Scene> scenes;
  size_t failures = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    AaRow& row = rows[i];
    std::fprintf(stderr, "[aa %zu/%zu] %s on %s %s: ", i + 1, rows.size(), row.aa.c_str(), row.scene.c_str(),
                 sizeText(row.size).c_str());
    try {
      if (!scenes.count(row.scene)) scenes.emplace(row.scene, loadSceneAny(row.scene));
      runRow(row, plan, scenes.at(row.scene), pipelineDir, shaders);
      std::fprintf(stderr, "%.1f ms, PSNR %.2f dB, edge PSNR %.2f dB (%zu edge pixels)\n", median(row.frameMs),
                   row.psnr, row.edgePsnr, row.edgePixels);
    } catch (const std::exception& e) {
      row.error = row.pipeline + ": " + e.what();
      std::fprintf(stderr, "failed\n");
      ++failures;
    }
    if (!timed) row.frameMs.clear();
  }
  return failures;
}

// ---------------------------------------------------------------- results

json aaJson(const AaRow& r) {
  const auto& fr = r.frameMs;
  json j = {{"axes", {"aa"}},
            {"scene", r.scene},
            {"aa", r.aa},
            {"pipeline", r.pipeline},
            {"width", r.size.width},
            {"height", r.size.height},
            {"frames", r.frames},
            {"frame_ms", fr},
            {"median_ms", median(fr)},
            {"min_ms", fr.empty() ? 0.0 : *std::min_element(fr.begin(), fr.end())},
            {"max_ms", fr.empty() ? 0.0 : *std::max_element(fr.begin(), fr.end())},
            {"psnr_db", r.psnr},
            {"edge_psnr_db", r.edgePsnr},
            {"edge_pixels", r.edgePixels},
            {"max_abs_error", r.maxAbs}};
  if (!r.ok()) j["error"] = r.error;
  return j;
}

AaRow aaFromJson(const json& j) {
  AaRow r;
  r.scene = j.at("scene");
  r.aa = j.at("aa");
  r.pipeline = j.at("pipeline");
  r.size = {j.at("width").get<uint32_t>(), j.at("height").get<uint32_t>()};
  r.frames = j.at("frames");
  r.frameMs = j.at("frame_ms").get<std::vector<double>>();
  r.psnr = j.at("psnr_db");
  r.edgePsnr = j.at("edge_psnr_db");
  r.edgePixels = j.at("edge_pixels");
  r.maxAbs = j.at("max_abs_error");
  if (j.contains("error")) r.error = j.at("error");
  return r;
}

void drawAaChart(const std::string& dir, const std::vector<AaRow>& rows, const std::string& machine) {
  using namespace chart;
  Chart c;
  c.title = "Anti-aliasing: frame time against edge error";
  c.notes = {machine,
             "error: PSNR over edge pixels against the pipeline at 4x4 supersampling; right is better; "
             "taa_orbit: mean over frames of a camera orbit"};
  c.xLabel = "edge PSNR dB (higher: closer to the 16-sample reference)";
  c.yLabel = "frame ms (median)";
  int color = 0;
  for (const auto& scene : kAaScenes) {
    Series s;
    s.name = scene + (rows.empty() ? "" : " " + sizeText(rows.front().size));
    s.color = color++;
    s.line = false;
    for (const auto& r : rows)
      if (r.ok() && r.scene == scene && !r.frameMs.empty()) s.points.push_back({r.edgePsnr, median(r.frameMs), r.aa});
    if (!s.points.empty()) c.series.push_back(std::move(s));
  }
  writeChart(c, dir, "aa_ms_vs_error");
}

}  // namespace rgraph::cli::bench
