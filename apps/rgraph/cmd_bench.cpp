// `rgraph bench`: speed against accuracy. Sweeps lighting methods, light
// counts, G-buffer layouts, light cut-off thresholds and resolutions on one
// scene, one axis at a time around a default point (plus the full method x
// light-count grid); times every point over repeated frames and measures its
// image against a reference (forward_lit with no cut-off into an rgba32f HDR
// target: no G-buffer quantisation at all). Writes results.csv,
// results.json, figures.md (the deterministic figures as the tables the docs
// quote) and three charts (SVG + PNG, drawn in C++: bench_chart.h). The aa
// axis (bench_aa.cpp) measures anti-aliasing methods on two scenes of its own
// against a 16-sample reference, with a fourth chart; the post axis
// (bench_post.h) bloom and SSAO methods; the shadows axis (bench_shadows.h)
// shadow filters, map sizes and cascades against exact visibility, with a
// chart of its own.
// This file runs the sweep; bench.h names the parts.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "bench.h"
#include "bench_aa_metrics.h"
#include "bench_post.h"
#include "bench_shadows.h"
#include "cli_common.h"
#include "cli_outputs.h"
#include "commands.h"
#include "rgraph/error.h"
#include "rgraph/output_file.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/shader_library.h"

namespace rgraph::cli {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;
using namespace bench;

// ---------------------------------------------------------------- progress

// ---------------------------------------------------------------- progress

class Progress {
 public:
  explicit Progress(double totalWeight) : total_(totalWeight), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()) {}

  void begin(size_t index, size_t count, const std::string& what) {
    index_ = index;
    count_ = count;
    if (tty_) draw(what);
  }
  void end(double weight, const std::string& what, const std::string& result) {
    done_ += weight;
    if (tty_) {
      draw(what);
    } else {
      std::cerr << "[" << index_ + 1 << "/" << count_ << "] " << what << ": " << result << " (elapsed "
                << clock(elapsed()) << ", ETA " << clock(eta()) << ")\n";
    }
  }
  void finish() {
    if (tty_) std::cerr << "\r\033[K";
    std::cerr.flush();
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double eta() const {
    if (done_ <= 0) return -1;
    return elapsed() / done_ * std::max(total_ - done_, 0.0);
  }
  static std::string clock(double s) {
    if (s < 0) return "--:--";
    const int t = static_cast<int>(std::lround(s));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%d:%02d", t / 60, t % 60);
    return buf;
  }
  void draw(const std::string& what) {
    const int width = 24;
    const double frac = total_ > 0 ? std::clamp(done_ / total_, 0.0, 1.0) : 0.0;
    const int filled = static_cast<int>(frac * width);
    std::string bar(static_cast<size_t>(filled), '#');
    bar.resize(width, '.');
    char head[96];
    std::snprintf(head, sizeof head, "[%s] %3d%% %zu/%zu ETA %s ", bar.c_str(), static_cast<int>(frac * 100),
                  index_ + 1, count_, clock(eta()).c_str());
    std::string line = head + what;
    if (line.size() > 110) line.resize(110);
    std::cerr << "\r\033[K" << line << std::flush;
  }

  double total_, done_ = 0;
  bool tty_;
  Clock::time_point start_;
  size_t index_ = 0, count_ = 0;
};

void writeText(const std::filesystem::path& path, const std::string& text) { writeOutputFile(path.string(), text); }

// The GL strings and the EGL device of a run's "machine" (contextJson), one
// line for figures.md; a run recorded before they were (an older
// results.json) says so.
std::string glText(const json& m) {
  auto get = [&](const char* key) {
    return m.contains(key) && m.at(key).is_string() ? m.at(key).get<std::string>() : std::string("not recorded");
  };
  std::string s = "GL_VENDOR " + get("vendor") + ", GL_RENDERER " + get("renderer") + ", GL_VERSION " +
                  get("version") + "; EGL platform " + get("platform");
  if (m.contains("egl_device") && m.at("egl_device").is_number_integer())
    s += ", device " + std::to_string(m.at("egl_device").get<int>()) + ": " + get("egl_device_description");
  return s + ".";
}

// figures.md: every table between the markers docs/performance.md uses, so a
// block can be pasted (scripts/update-bench-figures.py) and checked
// (tests/bench_cli).
std::string figuresMarkdown(const std::vector<Point>& points, const Config& def,
                            const std::vector<ShippedResult>& shipped, const std::vector<AaRow>& aa,
                            const std::vector<ShadowRow>& shadows, const std::string& sceneSpec,
                            const json& machine) {
  std::string s = "# rgraph bench: deterministic figures\n\nScene " + sceneSpec + "; default point " + describe(def) +
                  ". Error: 8-bit RGB against forward_lit with no cut-off into "
                  "an rgba32f target.\n" + glText(machine) + "\n";
  if (!aa.empty())
    s += "aa: each method against its own pipeline rendered at 4x4 the size with no jitter, box-filtered down "
         "(8-bit values); edge pixels: luma step of " +
         std::to_string(kEdgeThreshold) + "/255 to a neighbour in the reference.\n";
  if (!shadows.empty())
    s += "shadows: the lighting pass's image of scenes/shadows.json under each shadow method against the "
         "exact-visibility image (the ray caster's visibility per pixel and casting light), both tone-mapped as the "
         "pipeline does, 8-bit.\n";
  std::map<std::string, std::string> tables = figureTables(points, def, shipped, aa);
  if (!shadows.empty()) tables["shadows"] = shadowTable(shadows);
  for (const auto& [name, table] : tables)
    s += "\n<!-- bench-figures:" + name + " -->\n" + table + "<!-- /bench-figures:" + name + " -->\n";
  return s;
}

std::string machineText(const json& m) {
  return "OpenGL " + m.at("version").get<std::string>() + " on " + m.at("renderer").get<std::string>() + ", " +
         std::to_string(m.at("hardware_threads").get<unsigned>()) + " hardware threads";
}

// Before any work: the fixed-name files a run writes under --out are
// writable and are not its --scene or --replot file (cli_outputs.h).
bool checkBenchOutputs(const BenchOptions& options, const std::vector<std::string>& names) {
  std::vector<NamedPath> outputs;
  for (const auto& name : names)
    outputs.push_back({"--out " + name, (std::filesystem::path(options.out) / name).string()});
  return checkOutputs({{"--scene", options.scene}, {"--replot", options.replot}}, outputs);
}

// Redraws the charts and the figure tables of a previous run from its
// results.json (no rendering).
int replot(const BenchOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(options.out, ec);
  if (!checkBenchOutputs(options, {"figures.md"})) return kExitFailure;
  std::ifstream f(options.replot);
  if (!f) {
    std::cerr << "error: cannot read '" << options.replot << "'\n";
    return kExitFailure;
  }
  try {
    const json j = json::parse(f);
    const Config def = defaultPointFromJson(j);
    std::vector<Point> points;
    for (const json& pj : j.at("points")) points.push_back(pointFromJson(pj, def));
    const std::string spec = j.at("scene");
    std::filesystem::create_directories(options.out);
    std::vector<ShippedResult> shipped;
    for (const json& sj : j.value("shipped", json::array())) shipped.push_back(shippedFromJson(sj));
    std::vector<AaRow> aa;
    for (const json& aj : j.value("aa", json::array())) aa.push_back(aaFromJson(aj));
    std::vector<ShadowRow> shadows;
    for (const json& sj : j.value("shadows", json::array())) shadows.push_back(shadowFromJson(sj));
    writeText(std::filesystem::path(options.out) / "figures.md",
              figuresMarkdown(points, def, shipped, aa, shadows, spec, j.at("machine")));
    if (!points.empty())
      drawCharts(options.out, points, def, machineText(j.at("machine")),
                 sceneNote(spec, spec.rfind("many-lights", 0) == 0));
    if (!aa.empty()) drawAaChart(options.out, aa, machineText(j.at("machine")));
    if (!shadows.empty()) drawShadowChart(options.out, shadows, machineText(j.at("machine")));
  } catch (const std::exception& e) {
    std::cerr << "error: " << options.replot << ": " << e.what() << "\n";
    return kExitFailure;
  }
  std::cout << "wrote figures.md and the charts (.svg, .png) under " << options.out << "\n";
  return kExitOk;
}

struct RunPlan {
  int rounds = 1;
  FrameBudget budget, refBudget{0, 1, 1, 0};
  // A point whose frames take longer (ms) is timed in the first round only
  // (runSweep): its frames already span the load, and later rounds would cost
  // most of the run.
  double dearFrameMs = 3000;
};

// A point whose first frame takes longer is timed by that frame alone (the
// every-light loops at 4,096 and 10,000 lights at 1280x720: 20 to 80 s a
// frame; the fullscreen loop's first frame at 4,096 lights took 19.6 s
// against 19.2 s for its second, shader compilation included); three frames
// each would cost the full sweep ten minutes.
constexpr double kSingleFrameMs = 10000;

// Frames are spread over rounds: every point is measured once per round, so a
// change in machine load during the run (the machine is shared) touches every
// point alike instead of a few neighbours. --figures-only: one untimed frame.
RunPlan runPlan(const BenchOptions& o) {
  RunPlan r;
  if (o.smoke || o.figuresOnly) {
    r.budget = {0, 1, 1, 0};
  } else if (o.quick) {
    r.rounds = 2;
    r.budget = {2, 2, 3, 750, kSingleFrameMs};  // per round
    // --quick within 3 minutes of CPU on 2 cores (README): the every-light
    // loops at 256 and 1,024 lights (0.25-1.7 s a frame) once, not twice:
    // 223 -> 169 s of CPU (92 s wall); they keep 1 warm + 3 timed frames.
    r.dearFrameMs = 250;
  } else {
    r.rounds = 3;
    r.budget = {2, 2, 3, 1700, kSingleFrameMs};
  }
  return r;
}

Config refConfig(const Config& c) {
  Config r = c;
  r.method = "forward_lit";
  r.threshold = 0.0;
  return r;
}

std::string groupOf(const Config& c) {
  return sizeText(c.size) + "/" + std::to_string(c.lights) + (c.pillars ? "/pillars" : "");
}

// Renders every point once per round (and each group's reference once);
// returns the number of points that failed.
size_t runSweep(std::vector<Point>& points, Scenes& scenes, const RunPlan& plan, const Config& def,
                ShaderLibrary& shaders, GlContext& context) {
  auto weightOf = [&](const Config& c, const FrameBudget& b) {
    const double ms = estimateFrameMs(c);
    const int frames = b.singleFrameMs > 0 && ms > b.singleFrameMs
                           ? 1
                           : b.warm + std::clamp(static_cast<int>(b.budgetMs / std::max(ms, 1.0)), b.minFrames,
                                                 b.maxFrames);
    return ms * frames + 150.0;  // + building the executor (shaders are compiled once)
  };
  double totalWeight = 0;
  {
    std::set<std::string> groups;
    for (const auto& p : points) {
      const bool dear = estimateFrameMs(p.cfg) > plan.dearFrameMs;
      totalWeight += (dear ? 1 : plan.rounds) * weightOf(p.cfg, plan.budget);
      if (groups.insert(groupOf(p.cfg)).second) totalWeight += weightOf(refConfig(p.cfg), plan.refBudget);
    }
  }
  Progress progress(totalWeight);
  std::map<std::string, std::vector<uint8_t>> references;
  size_t failures = 0;
  const size_t steps = points.size() * static_cast<size_t>(plan.rounds);
  for (int round = 0; round < plan.rounds; ++round) {
    for (size_t i = 0; i < points.size(); ++i) {
      Point& p = points[i];
      if (!p.ok()) continue;
      // A dear point (the every-light loops at many lights) is timed in the
      // first round only (RunPlan::dearFrameMs).
      if (round > 0 && !p.m.frameMs.empty() && median(p.m.frameMs) > plan.dearFrameMs) continue;
      const size_t step = static_cast<size_t>(round) * points.size() + i;
      const Scene& scene = scenes.get(p.cfg.lights, p.cfg.pillars);
      const std::string group = groupOf(p.cfg);
      if (!references.count(group)) {
        const Config rc = refConfig(p.cfg);
        const std::string what =
            "reference (forward_lit, no cut-off) " + std::to_string(p.cfg.lights) + " lights " + sizeText(p.cfg.size) +
            (p.cfg.pillars ? " pillars" : "");
        progress.begin(step, steps, what);
        Measured ref =
            measure(pipelineJson(rc, true), "<bench reference>", scene, rc.size, shaders, context, plan.refBudget);
        references[group] = std::move(ref.image);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f ms", median(ref.frameMs));
        progress.end(weightOf(rc, plan.refBudget), what, buf);
      }
      std::string what = describe(p.cfg);
      if (plan.rounds > 1) what += " (round " + std::to_string(round + 1) + "/" + std::to_string(plan.rounds) + ")";
      progress.begin(step, steps, what);
      std::string result;
      try {
        Measured m = measure(pipelineJson(p.cfg, false), "<bench " + p.cfg.key() + ">", scene, p.cfg.size, shaders,
                             context, plan.budget);
        const double frameMs = median(m.frameMs);
        if (round == 0) {
          p.m = std::move(m);
          p.err = compareImages(p.m.image, references[group]);  // the image is kept for compareWithExact()
        } else {
          p.m.frameMs.insert(p.m.frameMs.end(), m.frameMs.begin(), m.frameMs.end());
          for (const auto& [pass, ms] : m.passMs) {
            if (!p.m.passMs.count(pass)) p.m.passOrder.push_back(pass);
            auto& all = p.m.passMs[pass];
            all.insert(all.end(), ms.begin(), ms.end());
          }
          p.m.glErrors += m.glErrors;
        }
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.1f ms, PSNR %.1f dB", frameMs, p.err.psnr);
        result = buf;
      } catch (const RuntimeError& e) {
        p.error = e.what();
        result = "failed";
        ++failures;
      }
      progress.end(weightOf(p.cfg, plan.budget), what, result);
    }
    if (round == 0) {
      compareWithExact(points, def);
      for (auto& p : points) std::vector<uint8_t>().swap(p.m.image);
    }
  }
  progress.finish();
  return failures;
}

const std::vector<std::string> kAxes = {"lights",    "lights_exact", "layout", "layout_exact",
                                        "threshold", "resolution",   "pillars",     "aa",          "post", "shadows"};

// --only lights keeps the exact loop at each N too (the methods' psnr_exact_db
// and the reference time need it); --only pillars keeps tiled and clustered
// on the field at the same counts (what the pillars are compared with).
bool keptByOnly(const Point& p, const std::string& only) {
  auto on = [&](const char* axis) { return std::count(p.axes.begin(), p.axes.end(), axis) > 0; };
  const bool pillarsPeer = only == "pillars" && on("lights") && p.cfg.lights >= 64 &&
                           (p.cfg.method == "tiled" || p.cfg.method == "clustered");
  return on(only.c_str()) || (only == "lights" && on("lights_exact")) || pillarsPeer;
}

// One line per scene: the methods' edge PSNR, and whether taa > fxaa > none
// by 2 dB each (the must-show), into results.json "checks".
void aaChecks(const std::vector<AaRow>& rows, json& checks, std::vector<std::string>& summary) {
  for (const auto& scene : kAaScenes) {
    std::map<std::string, double> edge;
    std::string line = "aa on " + scene + ", edge PSNR:";
    for (const auto& r : rows)
      if (r.ok() && r.scene == scene) {
        edge[r.aa] = r.edgePsnr;
        char buf[64];
        std::snprintf(buf, sizeof buf, " %s %.2f dB", r.aa.c_str(), r.edgePsnr);
        line += buf;
      }
    if (edge.size() < 2) continue;
    json j = json::object();
    for (const auto& [aa, db] : edge) j[aa + "_edge_psnr_db"] = db;
    if (edge.count("none") && edge.count("fxaa") && edge.count("taa")) {
      j["pass"] = edge["taa"] >= edge["fxaa"] + 2.0 && edge["fxaa"] >= edge["none"] + 2.0;
      line +=
          j["pass"].get<bool>() ? " (taa > fxaa > none by 2 dB each: yes)" : " (taa > fxaa > none by 2 dB each: NO)";
    }
    checks["aa_" + scene] = j;
    summary.push_back(line);
  }
}

}  // namespace

int runBench(const BenchOptions& options) {
  if (!options.replot.empty()) return replot(options);
  if (!options.only.empty() && !std::count(kAxes.begin(), kAxes.end(), options.only)) {
    std::string list;
    for (const auto& a : kAxes) list += (list.empty() ? "" : ", ") + a;
    std::cerr << "error: --only: unknown axis '" << options.only << "' (axes: " << list << ")\n";
    return kExitFailure;
  }
  const auto start = Clock::now();
  try {
    std::filesystem::create_directories(options.out);
  } catch (const std::exception& e) {
    std::cerr << "error: cannot create output folder '" << options.out << "': " << e.what() << "\n";
    return kExitFailure;
  }
  if (!checkBenchOutputs(options, {"results.csv", "results.json", "figures.md"})) return kExitFailure;
  try {
    Scenes scenes(options.smoke && options.scene.empty() ? "many-lights:4" : options.scene);
    auto context = GlContext::create(ContextOptions{});
    json machine = contextJson(context->device());
    machine["software"] = context->isSoftware();
    machine["hardware_threads"] = std::thread::hardware_concurrency();
    ShaderLibrary shaders;

    Config def;
    def.lights = scenes.defaultLights();
    if (options.smoke)
      def.size = {64, 64};
    else if (!options.quick)
      def.size = {1280, 720};  // the full sweep: every axis at 720p, lights up to 10,000
    std::vector<Point> points = planSweep(def, scenes, options.quick, options.smoke);
    if (!options.only.empty()) std::erase_if(points, [&](const Point& p) { return !keptByOnly(p, options.only); });
    const RunPlan plan = runPlan(options);
    size_t failures = runSweep(points, scenes, plan, def, shaders, *context);
    const std::string pipelineDir = std::filesystem::path(defaultPipelinePath()).parent_path().string();
    const AaPlan aaSettings = aaPlan(options.quick);
    std::vector<AaRow> aa;
    if (!options.smoke && (options.only.empty() || options.only == "aa")) {
      aa = planAa(aaSettings);
      failures += runAa(aa, aaSettings, pipelineDir, shaders, !options.figuresOnly);
    }
    // Bloom and SSAO methods at 1080p (bench_post.h): on their own (--only
    // post) or in a timed run (untimed, they are a minute of renders for a
    // few figures).
    std::vector<PostRow> post;
    if (!options.smoke && (options.only == "post" || (options.only.empty() && !options.figuresOnly))) {
      post = planPost(postPlan(options.quick));
      failures += runPost(post, postPlan(options.quick), pipelineDir, shaders);
    }
    // Shadow methods against exact visibility (bench_shadows.h): on their own
    // (--only shadows, --quick or not; with --smoke, four tiny rows for the
    // tests) or in the full timed run. Not in a plain --quick run: it would
    // double that run's CPU time (README), nor with --figures-only (its
    // figures are times against errors).
    std::vector<ShadowRow> shadows;
    ShadowReference shadowReference;
    if (options.only == "shadows" ||
        (options.only.empty() && !options.figuresOnly && !options.smoke && !options.quick)) {
      const ShadowPlan shadowSettings = shadowPlan(options.quick, options.smoke);
      shadows = planShadows(shadowSettings);
      failures += runShadows(shadows, shadowSettings, pipelineDir, shaders, shadowReference);
    }
    // The shipped pipelines as they come, on the default scene and size.
    std::vector<ShippedResult> shipped;
    if (!options.smoke && options.only.empty()) {
      std::cerr << "shipped pipelines against forward.json (" << scenes.spec() << ", " << def.lights << " lights, "
                << sizeText(def.size) << ")\n";
      shipped = measureShipped(pipelineDir, scenes.get(def.lights), def.size, shaders, *context);
    }
    // One untimed frame per point: no frame times to report.
    if (options.figuresOnly)
      for (auto& p : points) p.m.frameMs.clear(), p.m.passMs.clear(), p.m.passOrder.clear();

    // ---- outputs
    const std::filesystem::path dir(options.out);
    writeCsv((dir / "results.csv").string(), points, aa, shadows);
    std::vector<std::string> summary;
    json checks = headlineChecks(points, def, summary);
    aaChecks(aa, checks, summary);
    postChecks(post, checks, summary);
    shadowChecks(shadows, checks, summary);
    const double wallS = std::chrono::duration<double>(Clock::now() - start).count();
    json results = {{"tool", "rgraph bench"},
                    {"quick", options.quick},
                    {"figures_only", options.figuresOnly},
                    {"rounds", plan.rounds},
                    {"machine", machine},
                    {"scene", scenes.spec()},
                    {"default_point",
                     {{"method", def.method},
                      {"layout", def.layout},
                      {"threshold", def.threshold},
                      {"lights", def.lights},
                      {"width", def.size.width},
                      {"height", def.size.height}}},
                    {"reference",
                     "forward_lit, no cut-off, rgba32f HDR target, depth32f; "
                     "tonemap none (clamp), no gamma"},
                    {"lighting", {{"model", "blinn_phong"}, {"attenuation", "classic"}}},
                    {"timing", options.figuresOnly ? "none (--figures-only: one untimed frame per point)"
                                                   : "wall clock around renderFrame() + glFinish(), after "
                                                     "warm-up frames; "
                                                     "median, min, max over timed frames"},
                    {"error",
                     "8-bit RGB of the output against the reference: PSNR (capped "
                     "at 100 dB), max abs, "
                     "share of pixels with a channel off by more than 1/255"},
                    {"wall_seconds", wallS},
                    {"checks", checks},
                    {"only", options.only},
                    {"aa_reference",
                     "each method's pipeline at 4x4 the size, jitter off, one frame after a camera cut, "
                     "box-filtered down in 8-bit values (16 samples per pixel); edge pixels: luma step of " +
                         std::to_string(kEdgeThreshold) + "/255 to a 4-neighbour in the reference"},
                    {"points", json::array()}};
    for (const auto& p : points) results["points"].push_back(pointJson(p));
    results["shipped"] = json::array();
    for (const auto& r : shipped) results["shipped"].push_back(shippedJson(r));
    results["aa"] = json::array();
    for (const auto& r : aa) results["aa"].push_back(aaJson(r));
    results["post"] = json::array();
    for (const auto& r : post) results["post"].push_back(postJson(r));
    results["shadows"] = json::array();
    for (const auto& r : shadows) results["shadows"].push_back(shadowJson(r));
    if (!shadows.empty()) results["shadow_reference"] = shadowReferenceJson(shadowReference);
    writeText(dir / "results.json", results.dump(2) + "\n");
    writeText(dir / "figures.md", figuresMarkdown(points, def, shipped, aa, shadows, scenes.spec(), machine));
    if (!options.figuresOnly && !points.empty())
      drawCharts(options.out, points, def, machineText(machine), sceneNote(scenes.spec(), scenes.procedural()));
    if (!options.figuresOnly && !aa.empty()) drawAaChart(options.out, aa, machineText(machine));
    if (!shadows.empty()) drawShadowChart(options.out, shadows, machineText(machine));

    std::cout << "rgraph bench: " << points.size() << " points, " << aa.size() << " aa rows, " << shadows.size()
              << " shadows rows in "
              << static_cast<int>(wallS) << " s on " << describeContext(context->device())
              << (options.quick ? " (--quick)" : "") << (options.figuresOnly ? " (--figures-only)" : "") << "\n";
    for (const auto& s : summary) std::cout << "  " << s << "\n";
    std::cout << "wrote " << (dir / "results.csv").string() << ", results.json, figures.md"
              << (options.figuresOnly || points.empty() ? ""
                                                        : ", frame_ms_vs_lights, frame_ms_vs_error, "
                                                          "bytes_vs_error (.svg, .png)")
              << (options.figuresOnly || aa.empty() ? "" : ", aa_ms_vs_error (.svg, .png)")
              << (shadows.empty() ? "" : ", shadows_ms_vs_error (.svg, .png)") << "\n";
    if (failures) {
      std::cerr << "error: " << failures << " point(s) failed; see results.csv\n";
      for (const auto& p : points)
        if (!p.ok()) std::cerr << "  " << describe(p.cfg) << ": " << p.error << "\n";
      for (const auto& r : aa)
        if (!r.ok()) std::cerr << "  aa " << r.aa << " on " << r.scene << ": " << r.error << "\n";
      for (const auto& r : post)
        if (!r.ok()) std::cerr << "  post " << r.effect << " " << r.method << ": " << r.error << "\n";
      for (const auto& r : shadows)
        if (!r.ok()) std::cerr << "  shadows " << r.label() << ": " << r.error << "\n";
      return kExitFailure;
    }
  } catch (const RuntimeError& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace rgraph::cli
