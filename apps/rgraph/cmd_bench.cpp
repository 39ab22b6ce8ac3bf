// `rgraph bench`: speed against accuracy. Sweeps lighting methods, light
// counts, G-buffer layouts, light cut-off thresholds and resolutions on one
// scene, one axis at a time around a default point (plus the full method x
// light-count grid); times every point over repeated frames and measures its
// image against a reference (forward_lit with no cut-off into an rgba32f HDR
// target: no G-buffer quantisation at all). Writes results.csv,
// results.json and three charts (SVG + PNG, drawn in C++: bench_chart.h).
//
// Timing: wall clock around Executor::renderFrame() + glFinish(), after
// warm-up frames (shader compiles, first-touch allocations). On llvmpipe GL
// timer queries are wrong (see PLATFORM notes), so this is the only clock.
#include <GL/glcorearb.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "bench_chart.h"
#include "cli_common.h"
#include "commands.h"
#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace rgraph::cli {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;

// ---------------------------------------------------------------- what is swept

const std::vector<std::string> kMethods = {"forward_lit", "fullscreen", "fullscreen_radius", "light_volumes", "tiled"};
const std::vector<std::string> kLayouts = {"pbr", "learnopengl", "compact", "fp32"};
constexpr double kDefaultThreshold = 5.0 / 256.0;

std::string methodTitle(const std::string& m) {
  if (m == "forward_lit") return "forward_lit";
  if (m == "fullscreen") return "fullscreen loop";
  if (m == "fullscreen_radius") return "fullscreen + radius test";
  if (m == "light_volumes") return "light volumes";
  if (m == "tiled") return "tiled";
  return m;
}

struct Config {
  std::string method = "light_volumes";
  std::string layout = "pbr";  // unused by forward_lit
  double threshold = kDefaultThreshold;
  int lights = 256;
  Extent size{640, 360};

  bool deferred() const { return method != "forward_lit"; }
  std::string key() const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s|%s|%.8f|%d|%ux%u", method.c_str(), deferred() ? layout.c_str() : "-",
                  threshold, lights, size.width, size.height);
    return buf;
  }
};

std::string thresholdText(double t) {
  if (t <= 0.0) return "none";
  const double n = t * 256.0;
  char buf[32];
  if (std::abs(n - std::round(n)) < 1e-6)
    std::snprintf(buf, sizeof buf, "%d/256", static_cast<int>(std::lround(n)));
  else
    std::snprintf(buf, sizeof buf, "%.4g", t);
  return buf;
}

std::string sizeText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

std::string describe(const Config& c) {
  std::string s = c.method + " " + std::to_string(c.lights) + " lights";
  if (c.deferred()) s += " " + c.layout;
  return s + " cut-off " + thresholdText(c.threshold) + " " + sizeText(c.size);
}

// ---------------------------------------------------------------- pipelines as JSON

struct LayoutTargets {
  std::vector<std::pair<std::string, std::string>> color;  // slot -> format, in slot order
  std::string depth;
};

LayoutTargets layoutTargets(const std::string& layout) {
  if (layout == "learnopengl")
    return {{{"position", "rgba16f"}, {"normal", "rgba16f"}, {"albedo", "rgba8"}}, "depth24_stencil8"};
  if (layout == "compact") return {{{"normal", "rg16f"}, {"albedo", "rgba8"}, {"material", "rg8"}}, "depth32f"};
  if (layout == "fp32")
    return {{{"position", "rgba32f"}, {"normal", "rgba32f"}, {"albedo", "rgba32f"}, {"material", "rgba32f"}},
            "depth32f"};
  return {{{"position", "rgba16f"}, {"normal", "rgba16f"}, {"albedo", "rgba16f"}, {"material", "rgba16f"}},
          "depth24_stencil8"};  // pbr: 4 x 8 + 4 = 36 bytes per pixel
}

json lightingParams(const Config& c) {
  return {{"model", "blinn_phong"}, {"attenuation", "classic"}, {"threshold", c.threshold}};
}

// The reference: forward_lit, no cut-off, rgba32f HDR, depth32f.
std::string pipelineJson(const Config& c, bool reference) {
  json res = json::object(), passes = json::array();
  const std::string hdrFormat = reference || (c.deferred() && c.layout == "fp32") ? "rgba32f" : "rgba16f";
  res["hdr"] = {{"format", hdrFormat}, {"size", "output"}, {"clear", {0.0, 0.0, 0.0, 1.0}}};
  res["output"] = {{"format", "rgba8"}, {"size", "output"}};
  std::string lit = "hdr";
  if (reference || !c.deferred()) {
    res["depth"] = {{"format", "depth32f"}, {"size", "output"}};
    json params = lightingParams(c);
    if (reference) params["threshold"] = 0.0;
    passes.push_back({{"name", "forward_lit"}, {"type", "forward_lit"}, {"params", params},
                      {"outputs", {{"color", "hdr"}, {"depth", "depth"}}}});
  } else {
    const LayoutTargets t = layoutTargets(c.layout);
    json gOutputs = json::object(), gInputs = json::object();
    for (const auto& [slot, format] : t.color) {
      const std::string name = "g_" + slot;
      res[name] = {{"format", format}, {"size", "output"}};
      gOutputs[slot] = name;
      gInputs[slot] = name;
    }
    res["g_depth"] = {{"format", t.depth}, {"size", "output"}};
    gOutputs["depth"] = "g_depth";
    if (c.layout == "compact") gInputs["depth"] = "g_depth";  // position rebuilt from depth
    passes.push_back({{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", c.layout}}},
                      {"outputs", gOutputs}});
    json params = lightingParams(c);
    params["layout"] = c.layout;
    if (c.method == "fullscreen" || c.method == "fullscreen_radius") {
      params["radius_test"] = c.method == "fullscreen_radius";
      passes.push_back({{"name", "lighting"}, {"type", "deferred_lighting"}, {"params", params},
                        {"inputs", gInputs}, {"outputs", {{"color", "hdr"}}}});
    } else if (c.method == "light_volumes") {
      json ambient = params;
      ambient["point_lights"] = false;
      passes.push_back({{"name", "ambient"}, {"type", "deferred_lighting"}, {"params", ambient},
                        {"inputs", gInputs}, {"outputs", {{"color", "hdr"}}}});
      json vin = gInputs;
      if (c.layout == "compact") {
        // The volumes sample depth: test against a copy (no feedback loop).
        res["volume_depth"] = {{"format", t.depth}, {"size", "output"}};
        passes.push_back({{"name", "depth_copy"}, {"type", "depth_blit"}, {"inputs", {{"src", "g_depth"}}},
                          {"outputs", {{"dst", "volume_depth"}}}});
        vin["depth_test"] = "volume_depth";
      } else {
        vin["depth_test"] = "g_depth";
      }
      vin["color"] = "hdr";
      passes.push_back({{"name", "light_volumes"}, {"type", "light_volumes"}, {"params", params}, {"inputs", vin},
                        {"outputs", {{"color", "hdr_lit"}}}});
      lit = "hdr_lit";
    } else if (c.method == "tiled") {
      passes.push_back({{"name", "tiled"}, {"type", "tiled_deferred"}, {"params", params}, {"inputs", gInputs},
                        {"outputs", {{"color", "hdr"}}}});
    } else {
      throw RuntimeError("bench: unknown method '" + c.method + "'");
    }
  }
  passes.push_back({{"name", "tonemap"}, {"type", "tonemap"}, {"params", {{"operator", "none"}, {"gamma", 1.0}}},
                    {"inputs", {{"hdr", lit}}}, {"outputs", {{"output", "output"}}}});
  json doc = {{"version", 1}, {"description", "rgraph bench: " + describe(c)}, {"resources", res},
              {"passes", passes}, {"output", "output"}};
  return doc.dump(2);
}

PipelineConfig buildPipeline(const std::string& text, const std::string& name) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(text, name, diags);
  PipelineConfig cfg;
  if (doc.ok()) cfg = doc.build(PassRegistry::builtins(), diags);
  if (!doc.ok() || hasErrors(diags)) {
    std::string msg = "bench pipeline " + name + " has errors:";
    for (const auto& d : diags) msg += "\n  " + formatDiagnostic(d);
    throw RuntimeError(msg);
  }
  return cfg;
}

// ---------------------------------------------------------------- scenes

class Scenes {
 public:
  explicit Scenes(const std::string& spec) : spec_(spec.empty() ? "many-lights" : spec) {
    if (spec_.rfind("many-lights", 0) == 0) {
      procedural_ = true;
      // many-lights[:N[:seed]]
      std::vector<std::string> parts;
      std::stringstream ss(spec_);
      for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
      try {
        if (parts.size() > 1 && !parts[1].empty()) defaultLights_ = std::stoi(parts[1]);
        if (parts.size() > 2) seed_ = static_cast<uint32_t>(std::stoul(parts[2]));
      } catch (const std::exception&) {
        throw RuntimeError("bench: bad scene '" + spec_ + "' (many-lights[:N[:seed]])");
      }
      if (defaultLights_ < 1) defaultLights_ = 1;
    } else {
      base_ = std::make_unique<Scene>(loadSceneAny(spec_));
      defaultLights_ = static_cast<int>(base_->pointLights.size());
    }
  }
  bool procedural() const { return procedural_; }
  int defaultLights() const { return defaultLights_; }
  const std::string& spec() const { return spec_; }

  std::vector<int> lightCounts(bool quick) const {
    std::vector<int> wanted = {1, 4, 16, 64, 256, 1024};
    if (!quick) {
      wanted.push_back(4096);
      wanted.push_back(10000);
    }
    wanted.push_back(defaultLights_);
    std::set<int> counts;
    for (int n : wanted)
      if (procedural_ || n <= defaultLights_) counts.insert(n);
    return {counts.begin(), counts.end()};
  }

  const Scene& get(int lights) {
    auto it = cache_.find(lights);
    if (it != cache_.end()) return *it->second;
    std::unique_ptr<Scene> s;
    if (procedural_) {
      s = std::make_unique<Scene>(makeManyLightsScene(lights, seed_));
    } else {
      s = std::make_unique<Scene>(*base_);
      if (static_cast<size_t>(lights) < s->pointLights.size()) s->pointLights.resize(static_cast<size_t>(lights));
    }
    return *cache_.emplace(lights, std::move(s)).first->second;
  }

  std::string sceneName(int lights) const {
    return procedural_ ? "many-lights:" + std::to_string(lights) + (seed_ != 1 ? ":" + std::to_string(seed_) : "")
                       : spec_ + " (first " + std::to_string(lights) + " point lights)";
  }

 private:
  std::string spec_;
  bool procedural_ = false;
  int defaultLights_ = 256;
  uint32_t seed_ = 1;
  std::unique_ptr<Scene> base_;
  std::map<int, std::unique_ptr<Scene>> cache_;
};

// ---------------------------------------------------------------- running one pipeline

struct FrameBudget {
  int warm = 2;          // untimed frames first
  int minFrames = 3;     // timed frames, at least
  int maxFrames = 5;     // and at most
  double budgetMs = 1500;  // timed frames are cut to fit this
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

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Measured measure(const std::string& pipelineText, const std::string& name, const Scene& scene, Extent size,
                 ShaderLibrary& shaders, GlContext& context, const FrameBudget& budget) {
  const auto start = Clock::now();
  Measured m;
  PipelineConfig cfg = buildPipeline(pipelineText, name);
  {
    CompileOptions opts;
    opts.output = size;
    const Plan declared = compile(cfg.graph, opts);
    m.gbufferBytes = gbufferBytesPerPixel(cfg, declared);
  }
  adaptToScene(cfg, PassRegistry::builtins(), sceneFeatures(scene));  // as `rgraph render` does
  const uint64_t errorsBefore = context.debugErrorCount();
  Executor exec(cfg, PassRegistry::builtins(), shaders, &scene);
  exec.resize(size);
  m.gbufferBytesAdapted = gbufferBytesPerPixel(cfg, exec.plan());
  m.allocatedBytes = exec.plan().allocatedBytes;
  m.naiveBytes = exec.plan().naiveBytes;

  auto frame = [&]() {
    const auto t0 = Clock::now();
    exec.renderFrame();
    glFinish();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  for (int i = 0; i < budget.warm; ++i) {
    // The first frame compiles shaders; a dear point needs no second warm-up.
    if (frame() > budget.budgetMs / 3) break;
  }
  int target = budget.maxFrames;
  for (int i = 0; i < target; ++i) {
    const double ms = frame();
    m.frameMs.push_back(ms);
    for (const auto& t : exec.timings()) {
      if (!m.passMs.count(t.name)) m.passOrder.push_back(t.name);
      m.passMs[t.name].push_back(t.ms);
    }
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

struct ImageError {
  double psnr = 0;  // dB over RGB, capped at 100 (identical or nearly)
  int maxAbs = 0;   // 8-bit
  double over1 = 0;  // share of pixels with a channel off by more than 1/255
};
constexpr double kPsnrCap = 100.0;

ImageError compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& ref) {
  ImageError e;
  if (a.size() != ref.size() || a.empty()) return {0.0, 255, 1.0};
  double sq = 0;
  size_t over = 0;
  const size_t pixels = a.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(a[p * 4 + c]) - int(ref[p * 4 + c]));
      worst = std::max(worst, d);
      sq += double(d) * d;
    }
    e.maxAbs = std::max(e.maxAbs, worst);
    over += worst > 1;
  }
  e.over1 = double(over) / double(pixels);
  const double mse = sq / double(pixels * 3);
  e.psnr = mse > 0 ? std::min(kPsnrCap, 10.0 * std::log10(255.0 * 255.0 / mse)) : kPsnrCap;
  return e;
}

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

// A rough model of a point's cost (ms, 640x360 on llvmpipe with 2 threads),
// for the ETA only: the sweep grows from cheap to dear points.
double estimateFrameMs(const Config& c) {
  const double px = double(c.size.width) * c.size.height / (640.0 * 360.0);
  const double n = c.lights;
  double ms = 0;
  if (c.method == "forward_lit") ms = 10 + 0.5 * n;
  else if (c.method == "fullscreen") ms = 15 + 0.38 * n;
  else if (c.method == "fullscreen_radius") ms = 15 + 0.3 * n;
  else if (c.method == "light_volumes") ms = 20 + 0.06 * n;
  else ms = 20 + 0.05 * n;
  return ms * px;
}

// ---------------------------------------------------------------- results

struct Point {
  Config cfg;
  std::vector<std::string> axes;
  Measured m;
  ImageError err;
  std::string error;  // non-empty: the point failed (message)
  bool ok() const { return error.empty(); }
};

std::string csvEscape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string joined(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

void writeCsv(const std::string& path, const std::vector<Point>& points) {
  std::ofstream f(path);
  if (!f) throw RuntimeError("cannot write '" + path + "'");
  f << "axes,method,layout,threshold,lights,width,height,frames,median_ms,min_ms,max_ms,psnr_db,max_abs_error,"
       "share_over_1,gbuffer_bytes_per_pixel,gbuffer_bytes_per_pixel_adapted,allocated_bytes,naive_bytes,status\n";
  char buf[64];
  auto n = [&](double v, const char* fmt = "%.4f") {
    std::snprintf(buf, sizeof buf, fmt, v);
    return std::string(buf);
  };
  for (const auto& p : points) {
    const auto& fr = p.m.frameMs;
    const double mn = fr.empty() ? 0 : *std::min_element(fr.begin(), fr.end());
    const double mx = fr.empty() ? 0 : *std::max_element(fr.begin(), fr.end());
    f << csvEscape(joined(p.axes, ";")) << "," << p.cfg.method << "," << (p.cfg.deferred() ? p.cfg.layout : "")
      << "," << n(p.cfg.threshold, "%.8f") << "," << p.cfg.lights << "," << p.cfg.size.width << ","
      << p.cfg.size.height << "," << fr.size() << "," << n(median(fr)) << "," << n(mn) << "," << n(mx) << ","
      << n(p.err.psnr, "%.3f") << "," << p.err.maxAbs << "," << n(p.err.over1, "%.6f") << "," << p.m.gbufferBytes
      << "," << p.m.gbufferBytesAdapted << "," << p.m.allocatedBytes << "," << p.m.naiveBytes << ","
      << csvEscape(p.ok() ? "ok" : "error: " + p.error) << "\n";
  }
  if (!f) throw RuntimeError("cannot write '" + path + "'");
}

json pointJson(const Point& p) {
  const auto& fr = p.m.frameMs;
  json passes = json::array();
  for (const auto& name : p.m.passOrder) passes.push_back({{"name", name}, {"ms", median(p.m.passMs.at(name))}});
  json j = {{"axes", p.axes},
            {"method", p.cfg.method},
            {"layout", p.cfg.deferred() ? json(p.cfg.layout) : json(nullptr)},
            {"threshold", p.cfg.threshold},
            {"lights", p.cfg.lights},
            {"width", p.cfg.size.width},
            {"height", p.cfg.size.height},
            {"frames", fr.size()},
            {"frame_ms", fr},
            {"median_ms", median(fr)},
            {"min_ms", fr.empty() ? 0.0 : *std::min_element(fr.begin(), fr.end())},
            {"max_ms", fr.empty() ? 0.0 : *std::max_element(fr.begin(), fr.end())},
            {"passes", passes},
            {"psnr_db", p.err.psnr},
            {"max_abs_error", p.err.maxAbs},
            {"share_over_1", p.err.over1},
            {"gbuffer_bytes_per_pixel", p.m.gbufferBytes},
            {"gbuffer_bytes_per_pixel_adapted", p.m.gbufferBytesAdapted},
            {"allocated_bytes", p.m.allocatedBytes},
            {"naive_bytes", p.m.naiveBytes},
            {"gl_errors", p.m.glErrors}};
  if (!p.ok()) j["error"] = p.error;
  return j;
}

// ---------------------------------------------------------------- charts

bool sameConfig(const Config& a, const Config& b) { return a.key() == b.key(); }

void drawCharts(const std::string& dir, const std::vector<Point>& points, const Config& def, const std::string& machine,
                const std::string& sceneText) {
  using namespace chart;
  // 1. frame ms against light count, one line per method (the grid).
  {
    Chart c;
    c.title = "Frame time against light count (" + sizeText(def.size) + ", " + def.layout + " G-buffer, cut-off " +
              thresholdText(def.threshold) + ")";
    c.notes = {machine, sceneText};
    c.xLabel = "point lights";
    c.yLabel = "frame ms (median)";
    c.logX = c.logY = true;
    for (size_t mi = 0; mi < kMethods.size(); ++mi) {
      Series s;
      s.name = methodTitle(kMethods[mi]);
      s.color = static_cast<int>(mi);
      std::vector<const Point*> ps;
      for (const auto& p : points)
        if (p.ok() && p.cfg.method == kMethods[mi] && std::count(p.axes.begin(), p.axes.end(), "lights"))
          ps.push_back(&p);
      std::sort(ps.begin(), ps.end(), [](const Point* a, const Point* b) { return a->cfg.lights < b->cfg.lights; });
      for (const Point* p : ps) s.points.push_back({double(p->cfg.lights), median(p->m.frameMs), ""});
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    writeChart(c, dir, "frame_ms_vs_lights");
  }
  // 2. frame ms against error at the default scene and resolution, Pareto front marked.
  {
    Chart c;
    c.title = "Frame time against error (" + std::to_string(def.lights) + " lights, " + sizeText(def.size) + ")";
    c.notes = {machine, "error: PSNR against forward_lit with no cut-off (fp32 HDR); down and right is better; " +
                            std::string("PSNR capped at 100 dB")};
    c.xLabel = "PSNR dB (higher: closer to the reference)";
    c.yLabel = "frame ms (median)";
    c.logY = true;
    std::vector<chart::Point> all;
    std::vector<const Point*> src;
    for (size_t mi = 0; mi < kMethods.size(); ++mi) {
      Series s;
      s.name = methodTitle(kMethods[mi]);
      s.color = static_cast<int>(mi);
      s.line = false;
      for (const auto& p : points) {
        if (!p.ok() || p.cfg.method != kMethods[mi] || p.cfg.lights != def.lights || p.cfg.size != def.size) continue;
        s.points.push_back({p.err.psnr, median(p.m.frameMs), ""});
        all.push_back(s.points.back());
        src.push_back(&p);
      }
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    Series front;
    front.name = "Pareto front";
    front.color = 6;
    front.dashed = true;
    front.hollow = true;
    front.width = 1.5;
    for (size_t i : paretoFront(all, /*maximizeX=*/true, /*maximizeY=*/false)) {
      const Config& pc = src[i]->cfg;
      std::string label = pc.method == "forward_lit" ? "forward" : pc.method;
      if (pc.deferred()) label += " " + pc.layout;
      label += " " + thresholdText(pc.threshold);
      front.points.push_back({all[i].x, all[i].y, label});
    }
    if (!front.points.empty()) c.series.push_back(std::move(front));
    writeChart(c, dir, "frame_ms_vs_error");
  }
  // 3. G-buffer bytes per pixel against error, per layout.
  {
    Chart c;
    c.title = "G-buffer bytes per pixel against error (" + std::to_string(def.lights) + " lights, " +
              sizeText(def.size) + ")";
    c.notes = {machine, "bytes include depth; error: PSNR against forward_lit with no cut-off"};
    c.xLabel = "G-buffer bytes per pixel";
    c.yLabel = "PSNR dB";
    struct Mode {
      const char* axis;
      const char* name;
    };
    const Mode modes[] = {{"layout", "light volumes, cut-off 5/256"}, {"layout_exact", "fullscreen, no cut-off"}};
    int color = 0;
    for (const Mode& mode : modes) {
      Series s;
      s.name = mode.name;
      s.color = color++ == 0 ? 3 : 1;
      s.line = false;
      for (const std::string& layout : kLayouts)
        for (const auto& p : points)
          if (p.ok() && std::count(p.axes.begin(), p.axes.end(), mode.axis) && p.cfg.layout == layout)
            s.points.push_back({double(p.m.gbufferBytes), p.err.psnr, layout});
      std::sort(s.points.begin(), s.points.end(), [](const chart::Point& a, const chart::Point& b) { return a.x < b.x; });
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    writeChart(c, dir, "bytes_vs_error");
  }
}

std::string sceneNote(const std::string& spec, bool procedural) {
  return "scene: " + (procedural ? std::string("many-lights:N (field grows with N)") : spec) +
         "; Blinn-Phong, classic attenuation";
}

// Redraws the charts of a previous run from its results.json (no rendering).
int replot(const BenchOptions& options) {
  std::ifstream f(options.replot);
  if (!f) {
    std::cerr << "error: cannot read '" << options.replot << "'\n";
    return kExitFailure;
  }
  try {
    const json j = json::parse(f);
    const json& m = j.at("machine");
    const std::string machine = "OpenGL " + m.at("version").get<std::string>() + " on " +
                                m.at("renderer").get<std::string>() + ", " +
                                std::to_string(m.at("hardware_threads").get<unsigned>()) + " hardware threads";
    const json& d = j.at("default_point");
    Config def;
    def.method = d.at("method");
    def.layout = d.at("layout");
    def.threshold = d.at("threshold");
    def.lights = d.at("lights");
    def.size = {d.at("width").get<uint32_t>(), d.at("height").get<uint32_t>()};
    std::vector<Point> points;
    for (const json& pj : j.at("points")) {
      Point p;
      p.cfg.method = pj.at("method");
      p.cfg.layout = pj.at("layout").is_null() ? def.layout : pj.at("layout").get<std::string>();
      p.cfg.threshold = pj.at("threshold");
      p.cfg.lights = pj.at("lights");
      p.cfg.size = {pj.at("width").get<uint32_t>(), pj.at("height").get<uint32_t>()};
      p.axes = pj.at("axes").get<std::vector<std::string>>();
      p.m.frameMs = pj.at("frame_ms").get<std::vector<double>>();
      p.m.gbufferBytes = pj.at("gbuffer_bytes_per_pixel");
      p.err.psnr = pj.at("psnr_db");
      p.err.maxAbs = pj.at("max_abs_error");
      p.err.over1 = pj.at("share_over_1");
      if (pj.contains("error")) p.error = pj.at("error");
      points.push_back(std::move(p));
    }
    const std::string spec = j.at("scene");
    std::filesystem::create_directories(options.out);
    drawCharts(options.out, points, def, machine, sceneNote(spec, spec.rfind("many-lights", 0) == 0));
  } catch (const std::exception& e) {
    std::cerr << "error: " << options.replot << ": " << e.what() << "\n";
    return kExitFailure;
  }
  std::cout << "wrote frame_ms_vs_lights, frame_ms_vs_error, bytes_vs_error (.svg, .png) under " << options.out
            << "\n";
  return kExitOk;
}

}  // namespace

int runBench(const BenchOptions& options) {
  if (!options.replot.empty()) return replot(options);
  const auto start = Clock::now();
  try {
    std::filesystem::create_directories(options.out);
  } catch (const std::exception& e) {
    std::cerr << "error: cannot create output folder '" << options.out << "': " << e.what() << "\n";
    return kExitFailure;
  }
  try {
    Scenes scenes(options.smoke && options.scene.empty() ? "many-lights:4" : options.scene);
    auto context = GlContext::create(ContextOptions{});
    const std::string machine = "OpenGL " + context->version() + " on " + context->renderer() + ", " +
                                std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
    ShaderLibrary shaders;

    Config def;
    def.lights = scenes.defaultLights();
    if (options.smoke) def.size = {64, 64};

    // Points, each config once, with the axes it belongs to.
    std::vector<Point> points;
    std::map<std::string, size_t> byKey;
    auto add = [&](const Config& c, const std::string& axis) {
      auto it = byKey.find(c.key());
      if (it != byKey.end()) {
        auto& axes = points[it->second].axes;
        if (!std::count(axes.begin(), axes.end(), axis)) axes.push_back(axis);
        return;
      }
      byKey[c.key()] = points.size();
      points.push_back(Point{c, {axis}, {}, {}, {}});
    };
    if (options.smoke) {
      Config a = def;
      add(a, "smoke");
      a.method = "tiled";
      add(a, "smoke");
    } else {
      // The method x light-count grid.
      for (int n : scenes.lightCounts(options.quick))
        for (const auto& m : kMethods) {
          Config c = def;
          c.method = m;
          c.lights = n;
          add(c, "lights");
        }
      // Layouts: at the default point, and in the fullscreen loop with no
      // cut-off, where the layout is the only difference from the reference.
      for (const auto& l : kLayouts) {
        Config c = def;
        c.layout = l;
        add(c, "layout");
        c.method = "fullscreen";
        c.threshold = 0.0;
        add(c, "layout_exact");
      }
      // Cut-off thresholds, for both culling methods (they cull by the radius).
      for (double t : {1.0 / 256.0, 5.0 / 256.0, 20.0 / 256.0})
        for (const char* m : {"light_volumes", "tiled", "fullscreen_radius"}) {
          Config c = def;
          c.method = m;
          c.threshold = t;
          add(c, "threshold");
        }
      // Resolutions.
      std::vector<std::string> resMethods = {"light_volumes", "tiled"};
      if (!options.quick) resMethods = {"forward_lit", "fullscreen", "light_volumes", "tiled"};
      for (Extent s : {Extent{640, 360}, Extent{1280, 720}})
        for (const auto& m : resMethods) {
          Config c = def;
          c.method = m;
          c.size = s;
          add(c, "resolution");
        }
    }
    // Group by scene and size (references are rendered once per group), cheap first.
    std::stable_sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
      if (a.cfg.size.width * a.cfg.size.height != b.cfg.size.width * b.cfg.size.height)
        return a.cfg.size.width * a.cfg.size.height < b.cfg.size.width * b.cfg.size.height;
      return a.cfg.lights < b.cfg.lights;
    });

    // Frames are spread over rounds: every point is measured once per round,
    // so a change in machine load during the run (the machine is shared)
    // touches every point alike instead of a few neighbours.
    const int rounds = options.smoke ? 1 : options.quick ? 2 : 3;
    FrameBudget budget{2, 2, 3, 750};  // per round
    if (options.smoke) budget = {0, 1, 1, 0};
    else if (!options.quick) budget = {2, 2, 3, 1700};
    const FrameBudget refBudget = {0, 1, 1, 0};

    double totalWeight = 0;
    auto weightOf = [&](const Config& c, const FrameBudget& b) {
      const double ms = estimateFrameMs(c);
      const int frames = b.warm + std::clamp(static_cast<int>(b.budgetMs / std::max(ms, 1.0)), b.minFrames, b.maxFrames);
      return ms * frames + 150.0;  // + building the executor (shaders are compiled once)
    };
    auto refConfig = [](const Config& c) {
      Config r = c;
      r.method = "forward_lit";
      r.threshold = 0.0;
      return r;
    };
    auto groupOf = [](const Config& c) { return sizeText(c.size) + "/" + std::to_string(c.lights); };
    {
      std::set<std::string> groups;
      for (const auto& p : points) {
        totalWeight += rounds * weightOf(p.cfg, budget);
        if (groups.insert(groupOf(p.cfg)).second) totalWeight += weightOf(refConfig(p.cfg), refBudget);
      }
    }

    Progress progress(totalWeight);
    std::map<std::string, std::vector<uint8_t>> references;
    size_t failures = 0;
    for (int round = 0; round < rounds; ++round) {
      for (size_t i = 0; i < points.size(); ++i) {
        Point& p = points[i];
        if (!p.ok()) continue;
        const size_t step = static_cast<size_t>(round) * points.size() + i;
        const Scene& scene = scenes.get(p.cfg.lights);
        const std::string group = groupOf(p.cfg);
        if (!references.count(group)) {
          const Config rc = refConfig(p.cfg);
          const std::string what = "reference (forward_lit, no cut-off) " + std::to_string(p.cfg.lights) +
                                   " lights " + sizeText(p.cfg.size);
          progress.begin(step, points.size() * rounds, what);
          Measured ref = measure(pipelineJson(rc, true), "<bench reference>", scene, rc.size, shaders, *context,
                                 refBudget);
          references[group] = std::move(ref.image);
          char buf[64];
          std::snprintf(buf, sizeof buf, "%.1f ms", median(ref.frameMs));
          progress.end(weightOf(rc, refBudget), what, buf);
        }
        std::string what = describe(p.cfg);
        if (rounds > 1) what += " (round " + std::to_string(round + 1) + "/" + std::to_string(rounds) + ")";
        progress.begin(step, points.size() * rounds, what);
        std::string result;
        try {
          Measured m = measure(pipelineJson(p.cfg, false), "<bench " + p.cfg.key() + ">", scene, p.cfg.size, shaders,
                               *context, budget);
          const double frameMs = median(m.frameMs);
          if (round == 0) {
            p.m = std::move(m);
            p.err = compareImages(p.m.image, references[group]);
            p.m.image.clear();
            p.m.image.shrink_to_fit();
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
        progress.end(weightOf(p.cfg, budget), what, result);
      }
    }
    progress.finish();

    // ---- outputs
    const std::filesystem::path dir(options.out);
    writeCsv((dir / "results.csv").string(), points);

    json checks = json::object();
    auto find = [&](const Config& c) -> const Point* {
      for (const auto& p : points)
        if (p.ok() && sameConfig(p.cfg, c)) return &p;
      return nullptr;
    };
    std::vector<std::string> summary;
    char line[512];
    {
      // Light volumes or tiled against the fullscreen loop at 1,024 lights, 640x360.
      Config c = def;
      c.lights = 1024;
      c.size = {640, 360};
      c.method = "fullscreen";
      const Point* full = find(c);
      c.method = "light_volumes";
      const Point* vol = find(c);
      c.method = "tiled";
      const Point* tiled = find(c);
      if (full && (vol || tiled)) {
        const Point* best = vol && (!tiled || median(vol->m.frameMs) <= median(tiled->m.frameMs)) ? vol : tiled;
        const double speedup = median(full->m.frameMs) / median(best->m.frameMs);
        json j = {{"lights", 1024},
                  {"fullscreen_ms", median(full->m.frameMs)},
                  {"fullscreen_psnr_db", full->err.psnr},
                  {"best_method", best->cfg.method},
                  {"best_ms", median(best->m.frameMs)},
                  {"best_psnr_db", best->err.psnr},
                  {"speedup", speedup},
                  {"pass", speedup >= 5.0 && best->err.psnr >= full->err.psnr - 0.5}};
        if (vol) j["light_volumes_ms"] = median(vol->m.frameMs), j["light_volumes_psnr_db"] = vol->err.psnr;
        if (tiled) j["tiled_ms"] = median(tiled->m.frameMs), j["tiled_psnr_db"] = tiled->err.psnr;
        checks["culling_vs_fullscreen_1024"] = j;
        std::snprintf(line, sizeof line,
                      "1,024 lights %s: fullscreen loop %.1f ms (PSNR %.1f dB), light volumes %.1f ms (%.1f dB), "
                      "tiled %.1f ms (%.1f dB): %s %.1fx faster",
                      sizeText(c.size).c_str(), median(full->m.frameMs), full->err.psnr,
                      vol ? median(vol->m.frameMs) : 0.0, vol ? vol->err.psnr : 0.0,
                      tiled ? median(tiled->m.frameMs) : 0.0, tiled ? tiled->err.psnr : 0.0, best->cfg.method.c_str(),
                      speedup);
        summary.push_back(line);
      }
    }
    {
      // Compact layout: bytes per pixel and error where the layout is the only difference.
      Config c = def;
      c.method = "fullscreen";
      c.threshold = 0.0;
      c.layout = "compact";
      const Point* compact = find(c);
      c.layout = "pbr";
      const Point* pbr = find(c);
      if (compact) {
        json j = {{"bytes_per_pixel", compact->m.gbufferBytes},
                  {"bytes_per_pixel_adapted", compact->m.gbufferBytesAdapted},
                  {"psnr_db", compact->err.psnr},
                  {"max_abs_error", compact->err.maxAbs},
                  {"pass", compact->m.gbufferBytes <= 16 && compact->err.psnr >= 50.0}};
        if (pbr) j["pbr_bytes_per_pixel"] = pbr->m.gbufferBytes, j["pbr_psnr_db"] = pbr->err.psnr;
        checks["compact_layout"] = j;
        std::snprintf(line, sizeof line,
                      "compact layout: %u bytes/pixel with depth (pbr %u), PSNR %.1f dB, max error %d/255 "
                      "(fullscreen loop, no cut-off, %d lights)",
                      compact->m.gbufferBytes, pbr ? pbr->m.gbufferBytes : 0u, compact->err.psnr, compact->err.maxAbs,
                      c.lights);
        summary.push_back(line);
      }
    }
    {
      Config c = def;
      c.method = "forward_lit";
      const Point* fwd = find(c);
      c.method = "light_volumes";
      const Point* vol = find(c);
      if (fwd && vol) {
        const double speedup = median(fwd->m.frameMs) / median(vol->m.frameMs);
        checks["light_volumes_vs_forward"] = {{"lights", def.lights}, {"forward_ms", median(fwd->m.frameMs)},
                                              {"light_volumes_ms", median(vol->m.frameMs)}, {"speedup", speedup}};
        std::snprintf(line, sizeof line, "%d lights %s: forward_lit %.1f ms, light volumes %.1f ms: %.1fx faster",
                      def.lights, sizeText(def.size).c_str(), median(fwd->m.frameMs), median(vol->m.frameMs), speedup);
        summary.push_back(line);
      }
    }

    const double wallS = std::chrono::duration<double>(Clock::now() - start).count();
    json results = {
        {"tool", "rgraph bench"},
        {"quick", options.quick},
        {"rounds", rounds},
        {"machine", {{"renderer", context->renderer()}, {"version", context->version()},
                     {"software", context->isSoftware()}, {"hardware_threads", std::thread::hardware_concurrency()}}},
        {"scene", scenes.spec()},
        {"default_point", {{"method", def.method}, {"layout", def.layout}, {"threshold", def.threshold},
                           {"lights", def.lights}, {"width", def.size.width}, {"height", def.size.height}}},
        {"reference", "forward_lit, no cut-off, rgba32f HDR target, depth32f; tonemap none (clamp), no gamma"},
        {"lighting", {{"model", "blinn_phong"}, {"attenuation", "classic"}}},
        {"timing", "wall clock around renderFrame() + glFinish(), after warm-up frames; median, min, max over timed frames"},
        {"error", "8-bit RGB of the output against the reference: PSNR (capped at 100 dB), max abs, "
                  "share of pixels with a channel off by more than 1/255"},
        {"wall_seconds", wallS},
        {"checks", checks},
        {"points", json::array()}};
    for (const auto& p : points) results["points"].push_back(pointJson(p));
    {
      std::ofstream f(dir / "results.json");
      if (!f) throw RuntimeError("cannot write '" + (dir / "results.json").string() + "'");
      f << results.dump(2) << "\n";
    }
    drawCharts(options.out, points, def, machine, sceneNote(scenes.spec(), scenes.procedural()));

    std::cout << "rgraph bench: " << points.size() << " points in " << static_cast<int>(wallS) << " s on "
              << context->renderer() << (options.quick ? " (--quick)" : "") << "\n";
    for (const auto& s : summary) std::cout << "  " << s << "\n";
    std::cout << "wrote " << (dir / "results.csv").string() << ", results.json, frame_ms_vs_lights, frame_ms_vs_error, "
              << "bytes_vs_error (.svg, .png)\n";
    if (failures) {
      std::cerr << "error: " << failures << " point(s) failed; see results.csv\n";
      for (const auto& p : points)
        if (!p.ok()) std::cerr << "  " << describe(p.cfg) << ": " << p.error << "\n";
      return kExitFailure;
    }
  } catch (const RuntimeError& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace rgraph::cli
