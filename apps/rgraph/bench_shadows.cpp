// `rgraph bench`, the shadows axis: the rows, their pipelines, the
// exact-visibility image and the renders (bench_shadows.h says what is
// measured; bench_shadows_report.cpp writes it out).
#include "bench_shadows.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/image.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/registry.h"
#include "visibility_oracle.h"

namespace rgraph::cli::bench {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const char* kPipeline = "deferred-pbr-shadows.json";
// evsm rows: the moments pass and its resources of the shipped EVSM example,
// grafted onto the varied file (the filter needs the moments bound).
const char* kEvsmPipeline = "deferred-pbr-shadows-evsm.json";
const char* kMomentsPass = "moments";
const char* kScene = "shadows.json";  // under scenes/, next to pipelines/
const char* kLightingPass = "lighting";
const char* kShadowPass = "shadows";  // the shadow_map template: its expansions are "shadows.<light>..."
const char* kLitResource = "hdr";     // the lighting pass's output
constexpr int kDefaultSize = 2048, kDefaultCascades = 4;

struct Filter {
  const char* method;
  const char* filter;  // shadow_filter
  int taps;            // pcf_size (taps per side); 0: not set
};
const Filter kFilters[] = {{"hard", "hard", 0}, {"pcf3", "pcf", 3},  {"pcf5", "pcf", 5},
                           {"pcf7", "pcf", 7},  {"pcss", "pcss", 5}, {"evsm", "evsm", 0}};

const Filter& filterOf(const std::string& method) {
  for (const Filter& f : kFilters)
    if (method == f.method) return f;
  throw RuntimeError("bench: unknown shadow method '" + method + "'");
}

json& passNamed(json& pipeline, const std::string& name) {
  for (json& p : pipeline.at("passes"))
    if (p.at("name") == name) return p;
  throw RuntimeError(std::string(kPipeline) + " has no pass '" + name + "' (the shadows axis varies it)");
}

// The shipped file with shadows off: the lighting pass reads no atlas, so the
// shadow_map template has no reader and is culled with its atlas.
json shadowsOff(const json& shipped) {
  json p = shipped;
  json& lighting = passNamed(p, kLightingPass);
  lighting["params"]["shadows"] = false;
  for (const char* slot : {"shadows", "shadow_depths", "shadow_info"}) lighting["inputs"].erase(slot);
  return p;
}

// The EVSM example's moments pass, inserted before the lighting pass with
// the resources it binds, and the lighting pass reading its moments.
void addMoments(json& p, const json& evsm) {
  if (evsm.is_null()) throw RuntimeError(std::string("bench: evsm needs ") + kEvsmPipeline + " beside " + kPipeline);
  json source = evsm;
  const json moments = passNamed(source, kMomentsPass);
  for (const auto& [slot, resource] : moments.at("outputs").items())
    p["resources"][resource.get<std::string>()] = source.at("resources").at(resource.get<std::string>());
  json& passes = p.at("passes");
  for (auto it = passes.begin(); it != passes.end(); ++it)
    if (it->at("name") == kLightingPass) {
      passes.insert(it, moments);
      break;
    }
  passNamed(p, kLightingPass)["inputs"]["shadow_moments"] = moments.at("outputs").at("moments");
}

std::string variant(const json& shipped, const json& evsm, const ShadowRow& row) {
  if (row.method == "none") return shadowsOff(shipped).dump();
  json p = shipped;
  if (row.method == "evsm") addMoments(p, evsm);
  json& params = passNamed(p, kShadowPass)["params"];
  params["size"] = row.mapSize;
  params["cascades"] = row.cascades;
  const Filter& f = filterOf(row.method);
  json& lighting = passNamed(p, kLightingPass)["params"];
  lighting["shadow_filter"] = f.filter;
  if (f.taps > 0) lighting["pcf_size"] = f.taps;
  return p.dump();
}

// Empty when the lighting pass's type offers this filter; else why not (the
// row is then skipped: evsm turns on by itself once the type declares it).
std::string unsupported(const json& shipped, const std::string& method) {
  if (method == "none") return {};
  json copy = shipped;
  const std::string type = passNamed(copy, kLightingPass).at("type");
  const PassTypeDesc* desc = processRegistry().find(type);
  if (!desc) return "no pass type '" + type + "'";
  const std::string filter = filterOf(method).filter;
  for (const ParamDecl& d : desc->params)
    if (d.name == "shadow_filter") {
      if (std::count(d.choices.begin(), d.choices.end(), filter)) return {};
      std::string list;
      for (const auto& c : d.choices) list += (list.empty() ? "" : ", ") + c;
      return "the lighting pass type " + type + " does not offer shadow_filter " + filter + " (it offers " + list + ")";
    }
  return "the lighting pass type " + type + " has no shadow_filter param";
}

PipelineConfig build(const std::string& text, const std::string& what) {
  return loadPipelineTextOrThrow(text, std::string(kPipeline) + " (" + what + ")");
}

// The lighting pass's image (RGBA32F, rows top-down) as it is right after
// that pass, in a frame rendered now (what the forward pass draws after it is
// not part of it).
std::vector<float> litImage(Executor& exec) {
  const Plan& plan = exec.plan();
  size_t step = SIZE_MAX;
  for (const PlannedPass& p : plan.passes)
    if (p.name == kLightingPass && p.order.valid()) step = p.order.value();
  if (step == SIZE_MAX) throw RuntimeError(std::string(kPipeline) + ": the lighting pass does not run");
  std::vector<float> image;
  exec.setAfterPass([&](size_t s) {
    if (s == step) image = exec.readTextureRGBA32F(kLitResource);
  });
  exec.renderFrame();
  exec.setAfterPass({});
  if (image.empty()) throw RuntimeError("bench: the lighting pass's image was not read");
  return image;
}

std::vector<float> renderLit(const std::string& text, const std::string& what, const Scene& scene, Extent size,
                             ShaderLibrary& shaders) {
  PipelineConfig cfg = build(text, what);
  const std::unique_ptr<Executor> exec = makeExecutor(cfg, scene, size, shaders);
  return litImage(*exec);
}

// The pipeline's tone curve on the CPU (tonemap.frag's operators and the sRGB
// transfer its srgb8 output applies), rounded to 8 bits: the space the error
// is measured in, applied alike to every image compared.
struct ToneMap {
  std::string op = "aces";
  double exposure = 1.0;
  explicit ToneMap(const json& pipeline) {
    for (const json& p : pipeline.at("passes"))
      if (p.at("type") == "tonemap" && p.contains("params")) {
        op = p["params"].value("operator", op);
        exposure = p["params"].value("exposure", exposure);
      }
  }
  std::vector<uint8_t> operator()(const std::vector<float>& hdr) const {
    std::vector<uint8_t> out(hdr.size());
    for (size_t i = 0; i < hdr.size(); ++i) {
      if (i % 4 == 3) {
        out[i] = 255;
        continue;
      }
      double c = std::isfinite(hdr[i]) ? std::max(0.0, double(hdr[i])) * exposure : 0.0;
      if (op == "reinhard") c = c / (1.0 + c);
      if (op == "aces") c = (c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14);
      c = std::clamp(c, 0.0, 1.0);
      c = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
      out[i] = uint8_t(std::lround(c * 255.0));
    }
    return out;
  }
};

// ---- the exact-visibility image

// Per pixel (rows top-down), the surface the camera ray through its centre
// meets first; nullopt where none.
std::vector<std::optional<oracle::VisibilityOracle::Probe>> probes(const oracle::VisibilityOracle& o,
                                                                   const Camera& camera, Extent size) {
  const int w = int(size.width), h = int(size.height);
  std::vector<std::optional<oracle::VisibilityOracle::Probe>> out(size_t(w) * h);
  for (int row = 0; row < h; ++row)
    for (int x = 0; x < w; ++x)  // GL window coordinates: y from the bottom row
      out[size_t(row) * w + x] = o.probeAtPixel(camera, w, h, x + 0.5, (h - 1 - row) + 0.5);
  return out;
}

struct LightRef {
  std::string name;
  Scene alone, dark;  // the light alone, no ambient; and at intensity 0
  bool directional = false;
  size_t index = 0;
};

Scene withLights(const Scene& s, std::vector<PointLight> points, std::vector<DirectionalLight> suns,
                 glm::vec3 ambient) {
  Scene out = s;
  out.pointLights = std::move(points);
  out.directionalLights = std::move(suns);
  out.ambient = ambient;
  return out;
}

// exact: the exact-visibility image; unshadowed: the same sum with every
// visibility 1 (what the pipeline with shadows off must render).
struct Sums {
  std::vector<float> exact, unshadowed;
};

Sums exactImage(const json& shipped, const Scene& scene, Extent size, ShaderLibrary& shaders, ShadowReference& ref) {
  const std::string off = shadowsOff(shipped).dump();
  // base: ambient and the lights that cast no shadow.
  std::vector<PointLight> keptPoints;
  std::vector<DirectionalLight> keptSuns;
  std::vector<LightRef> casting;
  for (size_t i = 0; i < scene.directionalLights.size(); ++i) {
    const DirectionalLight& l = scene.directionalLights[i];
    if (!l.castShadows) {
      keptSuns.push_back(l);
      continue;
    }
    DirectionalLight dark = l;
    dark.intensity = 0.0f;
    casting.push_back({"directional" + std::to_string(i), withLights(scene, {}, {l}, glm::vec3(0.0f)),
                       withLights(scene, {}, {dark}, glm::vec3(0.0f)), true, i});
  }
  for (size_t i = 0; i < scene.pointLights.size(); ++i) {
    const PointLight& l = scene.pointLights[i];
    if (!l.castsShadows()) {
      keptPoints.push_back(l);
      continue;
    }
    PointLight dark = l;
    dark.intensity = 0.0f;
    casting.push_back({(l.spot ? "spot" : "point") + std::to_string(i), withLights(scene, {l}, {}, glm::vec3(0.0f)),
                       withLights(scene, {dark}, {}, glm::vec3(0.0f)), false, i});
  }
  if (casting.empty()) throw RuntimeError(std::string(kScene) + " has no shadow-casting light");
  Sums sums;
  std::vector<float>& sum = sums.exact;
  sum = renderLit(off, "reference: no casting light", withLights(scene, keptPoints, keptSuns, scene.ambient), size,
                  shaders);
  sums.unshadowed = sum;

  const auto t0 = std::chrono::steady_clock::now();
  const oracle::VisibilityOracle o(scene);
  const auto surface = probes(o, scene.camera, size);
  std::vector<size_t> pixel;  // probed pixels, in order
  std::vector<oracle::VisibilityOracle::Probe> list;
  for (size_t i = 0; i < surface.size(); ++i)
    if (surface[i]) pixel.push_back(i), list.push_back(*surface[i]);
  ref.pixels = list.size();
  double oracleSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  size_t shadowed = 0;
  for (const LightRef& l : casting) {
    ref.lights.push_back(l.name);
    const std::vector<float> lit = renderLit(off, "reference: " + l.name, l.alone, size, shaders);
    const std::vector<float> dark = renderLit(off, "reference: " + l.name + " dark", l.dark, size, shaders);
    const auto t1 = std::chrono::steady_clock::now();
    const std::vector<oracle::Visibility> vis = l.directional ? o.classify(list, scene.directionalLights[l.index])
                                                              : o.classify(list, scene.pointLights[l.index]);
    oracleSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    ref.shadowRays += list.size();
    // A pixel the camera ray misses has nothing to shadow: weight 1 (its
    // contribution is whatever the lighting pass leaves there, 0 or not).
    std::vector<float> weight(surface.size(), 1.0f);
    for (size_t k = 0; k < list.size(); ++k)
      if (vis[k] == oracle::Visibility::shadowed) weight[pixel[k]] = 0.0f, ++shadowed;
    for (size_t i = 0; i < sum.size(); ++i)
      if (i % 4 != 3) {
        sum[i] += weight[i / 4] * (lit[i] - dark[i]);
        sums.unshadowed[i] += lit[i] - dark[i];
      }
  }
  ref.oracleSeconds = oracleSeconds;
  ref.shadowedShare = ref.pixels ? double(shadowed) / double(ref.pixels * casting.size()) : 0.0;
  ref.how =
      "exact visibility from the ray caster (tests/support/visibility_oracle.h) at every pixel: base + sum over the " +
      std::to_string(casting.size()) +
      " casting lights of visibility x (the light alone - the light at intensity 0), each rendered with shadows off; "
      "the lighting pass's HDR image, tone-mapped on the CPU as the pipeline's tonemap pass";
  return sums;
}

// $RGRAPH_BENCH_SHADOW_IMAGES=DIR: the exact-visibility image and each row's,
// tone-mapped as compared, as PNGs (to look at what the figures measure).
void dumpImage(const std::string& name, Extent size, const std::vector<uint8_t>& rgba) {
  const char* dir = std::getenv("RGRAPH_BENCH_SHADOW_IMAGES");
  if (!dir || !*dir) return;
  std::string file = name;
  std::replace(file.begin(), file.end(), ' ', '_');
  fs::create_directories(dir);
  writePng((fs::path(dir) / (file + ".png")).string(), size.width, size.height, rgba);
}

// ---- one row

// Times the row's frames (appended to those of earlier rounds); in the first
// round (exact non-null) also its error, and for "none" its lit image.
void runRow(ShadowRow& row, const ShadowPlan& plan, const json& shipped, const json& evsm, const Scene& scene,
            ShaderLibrary& shaders, const std::vector<float>* exact, const ToneMap& tone,
            std::vector<float>* keepLit) {
  PipelineConfig cfg = build(variant(shipped, evsm, row), row.label());
  const std::unique_ptr<Executor> exec = makeExecutor(cfg, scene, row.size, shaders);
  const Plan& p = exec->plan();
  row.allocatedBytes = p.allocatedBytes;
  for (const PlannedResource& r : p.resources)
    if (r.name == "shadowAtlas" && r.physical.valid()) {
      row.atlasBytes = r.bytes;
      row.atlasLayers = p.physicalTexture(r.physical).layers;
    }
  for (int f = 0; f < plan.warm + plan.timedFrames; ++f) {
    const double ms = timedFrame(*exec);
    if (f < plan.warm) continue;
    row.frameMs.push_back(ms);
    if (!timedPasses(*exec)) continue;
    double shadow = 0.0;
    for (const auto& t : exec->timings())
      if (t.name.rfind(std::string(kShadowPass) + ".", 0) == 0) shadow += t.ms;
    row.shadowMs.push_back(shadow);
  }
  if (!exact) return;
  std::vector<float> lit = litImage(*exec);
  const std::vector<uint8_t> image = tone(lit);
  row.err = compareImages(image, tone(*exact));
  dumpImage(row.label(), row.size, image);
  if (keepLit) *keepLit = std::move(lit);
}

}  // namespace

std::string ShadowRow::label() const {
  if (method == "none") return "none";
  return method + " " + std::to_string(mapSize) + " c" + std::to_string(cascades);
}

ShadowPlan shadowPlan(bool quick, bool smoke) {
  ShadowPlan p;
  if (smoke) {
    p.size = {160, 90};
    p.warm = 0;
    p.timedFrames = 1;
    p.rounds = 1;
    p.tiny = true;
  } else if (quick) {
    p.timedFrames = 2;
  } else {
    p.size = {1280, 720};
    p.rounds = 3;
    p.everyMethodAtEveryResolution = true;
  }
  return p;
}

std::vector<ShadowRow> planShadows(const ShadowPlan& plan) {
  std::vector<ShadowRow> rows;
  auto add = [&](const std::string& method, int size, int cascades, const char* axis) {
    for (ShadowRow& r : rows)
      if (r.method == method && r.mapSize == size && r.cascades == cascades) {
        r.axes.push_back(axis);
        return;
      }
    ShadowRow r;
    r.method = method, r.mapSize = size, r.cascades = cascades, r.size = plan.size;
    r.axes = {axis};
    rows.push_back(std::move(r));
  };
  add("none", 0, 0, "baseline");
  if (plan.tiny) {  // the tests: the baseline, hard at two sizes, one filter
    add("hard", 512, kDefaultCascades, "resolution");
    add("hard", kDefaultSize, kDefaultCascades, "resolution");
    add("pcf3", kDefaultSize, kDefaultCascades, "method");
    return rows;
  }
  for (const Filter& f : kFilters) add(f.method, kDefaultSize, kDefaultCascades, "method");
  for (const Filter& f : kFilters) {
    const std::string m = f.method;
    if (!plan.everyMethodAtEveryResolution && m != "hard" && m != "pcf3") continue;
    for (int size : {512, 1024, 2048, 4096}) add(m, size, kDefaultCascades, "resolution");
  }
  for (const char* m : {"hard", "pcf3"})
    for (int c = 1; c <= 4; ++c) add(m, kDefaultSize, c, "cascades");
  return rows;
}

size_t runShadows(std::vector<ShadowRow>& rows, const ShadowPlan& plan, const std::string& pipelineDir,
                  ShaderLibrary& shaders, ShadowReference& reference) {
  const std::string file = (fs::path(pipelineDir) / kPipeline).string();
  const std::string sceneFile = (fs::path(pipelineDir).parent_path() / "scenes" / kScene).string();
  json shipped, evsm;  // evsm: null without the EVSM example (its rows then fail, saying so)
  Scene scene;
  Sums exact;
  try {
    std::ifstream in(file);
    if (!in) throw RuntimeError("cannot read " + file);
    std::stringstream text;
    text << in.rdbuf();
    shipped = json::parse(text.str());
    if (std::ifstream e{(fs::path(pipelineDir) / kEvsmPipeline).string()}) {
      std::stringstream evsmText;
      evsmText << e.rdbuf();
      evsm = json::parse(evsmText.str());
    }
    scene = loadSceneAny(sceneFile);
    std::fprintf(stderr, "[shadows] exact-visibility image of %s at %s: ", sceneFile.c_str(),
                 sizeText(plan.size).c_str());
    exact = exactImage(shipped, scene, plan.size, shaders, reference);
    dumpImage("exact_visibility", plan.size, ToneMap(shipped)(exact.exact));
    std::fprintf(stderr, "%zu lights, %zu pixels, %zu shadow rays in %.1f s\n", reference.lights.size(),
                 reference.pixels, reference.shadowRays, reference.oracleSeconds);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "failed: %s\n", e.what());
    for (auto& r : rows) r.error = e.what();
    return rows.size();
  }
  const ToneMap tone(shipped);
  size_t failures = 0;
  // Every row once per round (the error in the first): a change of machine
  // load during the run touches every row alike, not a few neighbours.
  for (int round = 0; round < plan.rounds; ++round) {
    for (size_t i = 0; i < rows.size(); ++i) {
      ShadowRow& row = rows[i];
      if (!row.ok() || (round > 0 && !row.skipped.empty())) continue;
      std::fprintf(stderr, "[shadows %zu/%zu, round %d/%d] %s at %s: ", i + 1, rows.size(), round + 1, plan.rounds,
                   row.label().c_str(), sizeText(row.size).c_str());
      row.skipped = unsupported(shipped, row.method);
      if (!row.skipped.empty()) {
        std::fprintf(stderr, "skipped: %s\n", row.skipped.c_str());
        continue;
      }
      try {
        std::vector<float> lit;
        runRow(row, plan, shipped, evsm, scene, shaders, round == 0 ? &exact.exact : nullptr, tone,
               row.method == "none" && round == 0 ? &lit : nullptr);
        if (!lit.empty()) {  // the same sum with every visibility 1 (bench_shadows.h)
          double worst = 0.0;
          for (size_t k = 0; k < lit.size(); ++k)
            if (k % 4 != 3) worst = std::max(worst, double(std::abs(lit[k] - exact.unshadowed[k])));
          reference.linearityMaxAbs = worst;
        }
        std::fprintf(stderr, "%.1f ms (shadow maps %.1f ms), PSNR %.2f dB, %.2f%% pixels off, atlas %.1f MiB\n",
                     median(row.frameMs), median(row.shadowMs), row.err.psnr, 100.0 * row.err.over1,
                     double(row.atlasBytes) / (1024.0 * 1024.0));
      } catch (const std::exception& e) {
        row.error = e.what();
        std::fprintf(stderr, "failed: %s\n", e.what());
        ++failures;
      }
    }
  }
  return failures;
}

}  // namespace rgraph::cli::bench
