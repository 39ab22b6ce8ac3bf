// `rgraph bench`, what is swept: the configurations (method, G-buffer layout,
// cut-off, light count, size), the pipeline each one renders (built here as
// config JSON from the built-in passes) and the scenes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "bench.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/error.h"
#include "rgraph/passes/gbuffer_layout.h"
#include "rgraph/registry.h"

namespace rgraph::cli::bench {

using nlohmann::json;

const std::vector<std::string> kMethods = {"forward_lit", "fullscreen", "fullscreen_radius", "light_volumes",
                                           "tiled",       "tiled_far",  "clustered",        "clustered_far"};
const std::vector<std::string> kLayouts = {"pbr", "learnopengl", "compact", "fp32"};

std::string Config::key() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s|%s|%.8f|%d|%ux%u%s", method.c_str(), deferred() ? layout.c_str() : "-", threshold,
                lights, size.width, size.height, pillars ? "|pillars" : "");
  return buf;
}

std::string methodTitle(const std::string& m) {
  if (m == "forward_lit") return "forward_lit";
  if (m == "fullscreen") return "fullscreen loop";
  if (m == "fullscreen_radius") return "fullscreen + radius test";
  if (m == "light_volumes") return "light volumes";
  if (m == "tiled") return "tiled";
  if (m == "tiled_far") return "tiled + far field";
  if (m == "clustered") return "clustered";
  if (m == "clustered_far") return "clustered + far field";
  return m;
}

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
  return s + " cut-off " + thresholdText(c.threshold) + " " + sizeText(c.size) + (c.pillars ? " pillars" : "");
}

// ---------------------------------------------------------------- pipelines as JSON

namespace {

// The G-buffer targets of a layout, in the formats of its table row.
const gbuffer::Layout& benchLayout(const std::string& name) {
  for (const auto& l : gbuffer::layouts())
    if (l.name == name) return l;
  throw RuntimeError("rgraph bench: no G-buffer layout '" + name + "' (layouts: " + gbuffer::nameList(false) + ")");
}

json lightingParams(const Config& c) {
  return {{"model", "blinn_phong"}, {"attenuation", "classic"}, {"threshold", c.threshold}};
}

}  // namespace

// The reference: forward_lit, no cut-off, rgba32f HDR, depth32f.
std::string pipelineJson(const Config& c, bool reference) {
  json res = json::object(), passes = json::array();
  const std::string hdrFormat =
      reference || (c.deferred() && c.layout == "fp32") ? "rgba32f" : "rgba16f";
  res["hdr"] = {{"format", hdrFormat}, {"size", "output"}, {"clear", {0.0, 0.0, 0.0, 1.0}}};
  res["output"] = {{"format", "rgba8"}, {"size", "output"}};
  std::string lit = "hdr";
  if (reference || !c.deferred()) {
    res["depth"] = {{"format", "depth32f"}, {"size", "output"}};
    json params = lightingParams(c);
    if (reference) params["threshold"] = 0.0;
    passes.push_back({{"name", "forward_lit"},
                      {"type", "forward_lit"},
                      {"params", params},
                      {"outputs", {{"color", "hdr"}, {"depth", "depth"}}}});
  } else {
    const gbuffer::Layout& layout = benchLayout(c.layout);
    const std::string depthFormat(formatName(layout.depth));
    json gOutputs = json::object(), gInputs = json::object();
    for (const auto& t : layout.targets) {
      if (t.optional) continue;  // the bench scenes have no emissive or specular materials
      const std::string name = "g_" + t.slot;
      res[name] = {{"format", formatName(t.format)}, {"size", "output"}};
      gOutputs[t.slot] = name;
      gInputs[t.slot] = name;
    }
    res["g_depth"] = {{"format", depthFormat}, {"size", "output"}};
    gOutputs["depth"] = "g_depth";
    if (layout.positionFromDepth) gInputs["depth"] = "g_depth";
    passes.push_back(
        {{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", c.layout}}}, {"outputs", gOutputs}});
    json params = lightingParams(c);
    params["layout"] = c.layout;
    if (c.method == "fullscreen" || c.method == "fullscreen_radius") {
      params["radius_test"] = c.method == "fullscreen_radius";
      passes.push_back({{"name", "lighting"},
                        {"type", "deferred_lighting"},
                        {"params", params},
                        {"inputs", gInputs},
                        {"outputs", {{"color", "hdr"}}}});
    } else if (c.method == "light_volumes") {
      json ambient = params;
      ambient["point_lights"] = false;
      passes.push_back({{"name", "ambient"},
                        {"type", "deferred_lighting"},
                        {"params", ambient},
                        {"inputs", gInputs},
                        {"outputs", {{"color", "hdr"}}}});
      json vin = gInputs;
      if (layout.positionFromDepth) {
        // The volumes sample depth: test against a copy (no feedback loop).
        res["volume_depth"] = {{"format", depthFormat}, {"size", "output"}};
        passes.push_back({{"name", "depth_copy"},
                          {"type", "depth_blit"},
                          {"inputs", {{"src", "g_depth"}}},
                          {"outputs", {{"dst", "volume_depth"}}}});
        vin["depth_test"] = "volume_depth";
      } else {
        vin["depth_test"] = "g_depth";
      }
      vin["color"] = "hdr";
      passes.push_back({{"name", "light_volumes"},
                        {"type", "light_volumes"},
                        {"params", params},
                        {"inputs", vin},
                        {"outputs", {{"color", "hdr_lit"}}}});
      lit = "hdr_lit";
    } else if (c.method == "tiled" || c.method == "tiled_far" || c.method == "clustered" ||
               c.method == "clustered_far") {
      const bool tiled = c.method.rfind("tiled", 0) == 0;
      if (c.method.find("_far") != std::string::npos) params["far_field"] = true;
      passes.push_back({{"name", c.method},
                        {"type", tiled ? "tiled_deferred" : "clustered_deferred"},
                        {"params", params},
                        {"inputs", gInputs},
                        {"outputs", {{"color", "hdr"}}}});
    } else {
      throw RuntimeError("bench: unknown method '" + c.method + "'");
    }
  }
  passes.push_back({{"name", "tonemap"},
                    {"type", "tonemap"},
                    {"params", {{"operator", "none"}, {"gamma", 1.0}}},
                    {"inputs", {{"hdr", lit}}},
                    {"outputs", {{"output", "output"}}}});
  json doc = {{"version", 1},
              {"description", "rgraph bench: " + describe(c)},
              {"resources", res},
              {"passes", passes},
              {"output", "output"}};
  return doc.dump(2);
}

PipelineConfig buildPipeline(const std::string& text, const std::string& name) {
  return loadPipelineTextOrThrow(text, "bench pipeline " + name);
}

const std::vector<ShippedMethod> kShippedMethods = {
    {"deferred-light-volumes.json", "deferred-light-volumes.json"},
    {"the same, rgba32f position", "deferred-light-volumes.json", true},
    {"deferred-blinn-phong.json at 5/256", "deferred-blinn-phong.json", false, "lighting"},
    {"deferred-tiled.json", "deferred-tiled.json"},
    {"the same, rgba32f position", "deferred-tiled.json", true},
};

void applyShippedVariant(const ShippedMethod& m, PipelineConfig& cfg) {
  if (m.fp32Position)
    for (auto& r : cfg.graph.resources)
      if (r.name == "gPosition") r.texture.format = Format::rgba32f;
  if (m.cutOffPass)
    for (size_t i = 0; i < cfg.graph.passes.size(); ++i)
      if (cfg.graph.passes[i].name == m.cutOffPass) cfg.params[i].set("threshold", kDefaultThreshold);
}

// ---------------------------------------------------------------- scenes

Scenes::Scenes(const std::string& spec) : spec_(spec.empty() ? "many-lights" : spec) {
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

Scenes::~Scenes() = default;

std::vector<int> Scenes::lightCounts(bool quick) const {
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

const Scene& Scenes::get(int lights, bool pillars) {
  auto it = cache_.find({lights, pillars});
  if (it != cache_.end()) return *it->second;
  std::unique_ptr<Scene> s;
  if (procedural_) {
    s = std::make_unique<Scene>(pillars ? makeManyLightsPillarsScene(lights, seed_) : makeManyLightsScene(lights, seed_));
  } else {
    s = std::make_unique<Scene>(*base_);
    if (static_cast<size_t>(lights) < s->pointLights.size()) s->pointLights.resize(static_cast<size_t>(lights));
  }
  return *cache_.emplace(std::make_pair(lights, pillars), std::move(s)).first->second;
}

// ---------------------------------------------------------------- the sweep

std::vector<Point> planSweep(const Config& def, const Scenes& scenes, bool quick, bool smoke) {
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
    Point p;
    p.cfg = c;
    p.axes = {axis};
    points.push_back(std::move(p));
  };
  if (smoke) {
    Config a = def;
    add(a, "smoke");
    a.method = "tiled";
    add(a, "smoke");
  } else {
    // The method x light-count grid.
    for (int n : scenes.lightCounts(quick))
      for (const auto& m : kMethods) {
        Config c = def;
        c.method = m;
        c.lights = n;
        add(c, "lights");
      }
    // The exact loop at every light count: the reference time at each N,
    // and the image each method's psnr_exact_db is measured against.
    for (int n : scenes.lightCounts(quick)) {
      Config c = def;
      c.lights = n;
      add(exactConfig(c, def), "lights_exact");
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
    // Depth discontinuities: tiled against clustered on the pillars variant
    // of the procedural scene, where a screen tile holds pixels near the
    // camera and at the far wall (the field's points are on "lights").
    if (scenes.procedural())
      for (int n : scenes.lightCounts(quick))
        for (const char* m : {"tiled", "clustered"}) {
          if (n < 64) continue;
          Config c = def;
          c.method = m;
          c.lights = n;
          c.pillars = true;
          add(c, "pillars");
        }
    // Resolutions.
    std::vector<std::string> resMethods = {"light_volumes", "tiled"};
    if (!quick) resMethods = {"forward_lit", "fullscreen", "light_volumes", "tiled"};
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
  return points;
}

Config exactConfig(const Config& c, const Config& def) {
  Config e = def;
  e.method = "fullscreen";
  e.threshold = 0.0;
  e.lights = c.lights;
  e.size = c.size;
  e.pillars = c.pillars;
  return e;
}

void compareWithExact(std::vector<Point>& points, const Config& def) {
  std::map<std::string, const Point*> byKey;
  for (const auto& p : points)
    if (p.ok() && !p.m.image.empty()) byKey[p.cfg.key()] = &p;
  for (auto& p : points) {
    auto it = byKey.find(exactConfig(p.cfg, def).key());
    if (!p.ok() || p.m.image.empty() || it == byKey.end()) continue;
    p.errExact = compareImages(p.m.image, it->second->m.image);
    p.hasExact = true;
  }
}

}  // namespace rgraph::cli::bench
