#include "stability_util.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "rgraph/error.h"
#include "support/test_support.h"
#include "rgraph/image.h"
#include "rgraph/pipeline_load.h"

namespace rgraph::stab {

namespace {
std::unique_ptr<ShaderLibrary>& shadersSlot() {
  static std::unique_ptr<ShaderLibrary> lib;
  return lib;
}
}  // namespace

GlContext& glContext() { return testsupport::sharedGlContext(); }

ShaderLibrary& sharedShaders() {
  glContext();
  auto& lib = shadersSlot();
  if (!lib) {
    lib = std::make_unique<ShaderLibrary>();
    // Its programs must go before the context does.
    testsupport::destroyBeforeContext([] { shadersSlot().reset(); });
  }
  return *lib;
}

void Stability::SetUp() {
  try {
    glContext();
  } catch (const RuntimeError& e) {
    FAIL() << "no headless GL context: " << e.what();
  }
  errorsAtStart = glContext().debugErrorCount();
}

void Stability::TearDown() {
  if (testsupport::hasSharedGlContext()) {
    EXPECT_EQ(glContext().debugErrorCount(), errorsAtStart) << "GL debug errors, last: " << glContext().lastDebugError();
  }
}

// ---------------------------------------------------------------- pipelines

PipelineConfig pipelineFromJson(const nlohmann::json& doc, const std::string& name) {
  const std::string text = doc.dump(2);
  return testsupport::buildPipelineOrThrow(text, name, text);
}

PipelineConfig repoPipeline(const std::string& name) {
  return testsupport::loadPipelineOrThrow(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + name);
}

void setParam(PipelineConfig& cfg, const std::string& pass, const std::string& key, ParamValue value) {
  for (size_t i = 0; i < cfg.graph.passes.size(); ++i) {
    if (cfg.graph.passes[i].name == pass) {
      cfg.params[i].set(key, std::move(value));
      return;
    }
  }
  throw RuntimeError("setParam: no pass named '" + pass + "'");
}

namespace {
using nlohmann::json;

json texture(const std::string& format, const json& clear = nullptr) {
  json r = {{"format", format}, {"size", "output"}};
  if (!clear.is_null()) r["clear"] = clear;
  return r;
}

// Resources, geometry outputs and the sampled inputs of a lighting pass for one layout.
struct GBufferJson {
  json resources = json::object();
  json outputs = json::object();  // geometry pass
  json inputs = json::object();   // lighting passes (sampled G-buffer slots)
};

GBufferJson gbuffer(const GBufferSpec& g) {
  GBufferJson j;
  std::string pos, nrm, alb, mat, depth;
  if (g.layout == "learnopengl") {
    pos = "rgba16f", nrm = "rgba16f", alb = "rgba8", depth = "depth24_stencil8";
  } else if (g.layout == "pbr") {
    pos = "rgba16f", nrm = "rgba16f", alb = "rgba16f", mat = "rgba16f", depth = "depth32f";
  } else if (g.layout == "compact") {
    nrm = "rg16f", alb = "rgba8", mat = "rg8", depth = "depth24_stencil8";
  } else if (g.layout == "fp32") {
    pos = "rgba32f", nrm = "rgba32f", alb = "rgba32f", mat = "rgba32f", depth = "depth32f";
  } else {
    throw RuntimeError("unknown layout " + g.layout);
  }
  if (!g.depthFormat.empty()) depth = g.depthFormat;
  auto add = [&](const char* slot, const char* name, const std::string& format) {
    if (format.empty()) return;
    j.resources[name] = texture(format);
    j.outputs[slot] = name;
    j.inputs[slot] = name;
  };
  add("position", "gPosition", pos);
  add("normal", "gNormal", nrm);
  add("albedo", "gAlbedo", alb);
  add("material", "gMaterial", mat);
  j.resources["gDepth"] = texture(depth);
  j.outputs["depth"] = "gDepth";
  if (g.layout == "compact") j.inputs["depth"] = "gDepth";  // position rebuilt from depth
  return j;
}

json lightingParams(const LightingParams& l, const std::string& layout) {
  return {{"layout", layout}, {"model", l.model}, {"attenuation", l.attenuation}, {"threshold", l.threshold}};
}

json tonemapPass(const std::string& hdrVersion, double gamma) {
  return {{"name", "tonemap"},
          {"type", "tonemap"},
          {"params", {{"operator", "none"}, {"gamma", gamma}}},
          {"inputs", {{"hdr", hdrVersion}}},
          {"outputs", {{"output", "output"}}}};
}
}  // namespace

nlohmann::json fullscreenPipeline(const GBufferSpec& g, const LightingParams& l, double gamma) {
  const GBufferJson gb = gbuffer(g);
  json doc = {{"version", 1}, {"description", "stability test: fullscreen deferred lighting, " + g.layout + " layout"}};
  doc["resources"] = gb.resources;
  doc["resources"]["hdr"] = texture("rgba32f", json::array({0.0, 0.0, 0.0, 1.0}));
  doc["resources"]["output"] = texture("rgba8");
  doc["passes"] = json::array({
      {{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", g.layout}}}, {"outputs", gb.outputs}},
      {{"name", "lighting"},
       {"type", "deferred_lighting"},
       {"params", lightingParams(l, g.layout)},
       {"inputs", gb.inputs},
       {"outputs", {{"color", "hdr"}}}},
      tonemapPass("hdr", gamma),
  });
  doc["output"] = "output";
  return doc;
}

nlohmann::json computePipeline(const std::string& type, const LightingParams& l, const nlohmann::json& extraParams) {
  nlohmann::json doc = fullscreenPipeline({"fp32", ""}, l);
  for (nlohmann::json& pass : doc["passes"])
    if (pass["name"] == "lighting") {
      pass["type"] = type;
      pass["params"].update(extraParams);
    }
  return doc;
}

nlohmann::json lightVolumesPipeline(const std::string& cull, const LightingParams& l, double gamma) {
  const GBufferJson gb = gbuffer({"fp32", ""});
  json doc = {{"version", 1}, {"description", "stability test: light volumes, cull " + cull}};
  doc["resources"] = gb.resources;
  doc["resources"]["hdr"] = texture("rgba32f", json::array({0.0, 0.0, 0.0, 1.0}));
  doc["resources"]["output"] = texture("rgba8");
  json ambient = lightingParams(l, "fp32");
  ambient["point_lights"] = false;
  json volumes = lightingParams(l, "fp32");
  volumes["cull"] = cull;
  json volumeInputs = gb.inputs;
  volumeInputs["depth_test"] = "gDepth";
  volumeInputs["color"] = "hdr";
  doc["passes"] = json::array({
      {{"name", "gbuffer"}, {"type", "geometry"}, {"params", {{"layout", "fp32"}}}, {"outputs", gb.outputs}},
      {{"name", "ambient"},
       {"type", "deferred_lighting"},
       {"params", ambient},
       {"inputs", gb.inputs},
       {"outputs", {{"color", "hdr"}}}},
      {{"name", "volumes"},
       {"type", "light_volumes"},
       {"params", volumes},
       {"inputs", volumeInputs},
       {"outputs", {{"color", "hdr_lit"}}}},
      tonemapPass("hdr_lit", gamma),
  });
  doc["output"] = "output";
  return doc;
}

nlohmann::json forwardPipeline(const LightingParams& l, double gamma) {
  json doc = {{"version", 1}, {"description", "stability test: forward_lit reference"}};
  doc["resources"] = {{"hdr", texture("rgba32f", json::array({0.0, 0.0, 0.0, 1.0}))},
                      {"depth", texture("depth32f")},
                      {"output", texture("rgba8")}};
  json params = {{"model", l.model}, {"attenuation", l.attenuation}, {"threshold", l.threshold}};
  doc["passes"] = json::array({
      {{"name", "forward_lit"}, {"type", "forward_lit"}, {"params", params},
       {"outputs", {{"color", "hdr"}, {"depth", "depth"}}}},
      tonemapPass("hdr", gamma),
  });
  doc["output"] = "output";
  return doc;
}

// ---------------------------------------------------------------- frames

Frame renderFrame(const PipelineConfig& cfg, const Scene& scene, Extent size, const std::vector<std::string>& targets) {
  Executor exec(cfg, processRegistry(), sharedShaders(), &scene);
  exec.resize(size);
  exec.renderFrame();
  Frame f;
  f.size = exec.outputExtent();
  f.rgba = exec.readOutputRGBA8();
  for (const auto& t : targets) f.targets[t] = exec.readTextureRGBA32F(t);
  return f;
}

bool liveToTheEnd(const Plan& plan, const std::string& resource, std::string* why) {
  int index = -1;
  for (size_t r = 0; r < plan.resources.size(); ++r) {
    const auto& pr = plan.resources[r];
    if (pr.name == resource || std::find(pr.versions.begin(), pr.versions.end(), resource) != pr.versions.end())
      index = static_cast<int>(r);
  }
  if (index < 0) {
    if (why) *why = "no resource '" + resource + "'";
    return false;
  }
  const PlannedResource& me = plan.resources[index];
  if (!me.physical.valid()) return true;  // its own texture
  for (ResourceIndex other : plan.physicalTexture(me.physical).resources) {
    if (other == ResourceIndex(static_cast<uint32_t>(index))) continue;
    const PlannedResource& o = plan.resource(other);
    if (o.firstPass > me.lastPass) {
      if (why) *why = "'" + o.name + "' reuses its texture after its last use";
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------- metrics

std::string psnrText(double psnr) {
  if (std::isinf(psnr)) return "inf dB";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f dB", psnr);
  return buf;
}

std::string Diff::describe() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "max %d/255, PSNR %s, %zu of %zu pixels off by more than 1/255", maxAbs,
                psnrText(psnr).c_str(), over1, pixels);
  std::string s = buf;
  if (worstX >= 0) s += " (worst at " + std::to_string(worstX) + "," + std::to_string(worstRow) + ")";
  return s;
}

size_t pixelsBrighter(const Frame& a, const Frame& b, int by) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < a.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      if (int(a.rgba[i + c]) - int(b.rgba[i + c]) >= by) {
        ++n;
        break;
      }
  return n;
}

Diff compare8(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, Extent e, const std::vector<bool>* mask) {
  Diff d;
  const size_t n = static_cast<size_t>(e.width) * e.height;
  if (a.size() != n * 4 || b.size() != n * 4) throw RuntimeError("compare8: image sizes differ");
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (mask && !(*mask)[i]) continue;
    ++d.pixels;
    int m = 0;
    for (int c = 0; c < 3; ++c) {
      const int delta = std::abs(int(a[i * 4 + c]) - int(b[i * 4 + c]));
      sum += double(delta) * delta;
      m = std::max(m, delta);
    }
    if (m > 1) ++d.over1;
    if (m > d.maxAbs) {
      d.maxAbs = m;
      d.worstX = static_cast<int>(i % e.width);
      d.worstRow = static_cast<int>(i / e.width);
    }
  }
  d.mse = d.pixels ? sum / (3.0 * double(d.pixels)) : 0.0;
  d.psnr = d.mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / d.mse) : std::numeric_limits<double>::infinity();
  return d;
}

std::string saveImage(const std::vector<uint8_t>& rgba, Extent e, const std::string& name) {
  try {
    std::filesystem::create_directories("stability-output");
    const std::string path = (std::filesystem::current_path() / "stability-output" / (name + ".png")).string();
    writePng(path, e.width, e.height, rgba);
    return path;
  } catch (const std::exception&) {
    return "";
  }
}

double halfUlp(double v) {
  v = std::abs(v);
  if (v < 6.103515625e-05) return std::ldexp(1.0, -24);  // subnormals
  return std::ldexp(1.0, static_cast<int>(std::floor(std::log2(v))) - 10);
}

// ---------------------------------------------------------------- scenes

PointLight pointLight(glm::vec3 pos, glm::vec3 color, float intensity, float constant, float linear, float quadratic) {
  PointLight l;
  l.position = pos;
  l.color = color;
  l.intensity = intensity;
  l.constant = constant;
  l.linear = linear;
  l.quadratic = quadratic;
  l.radius = lightRadius(l);
  return l;
}

void placeCamera(Scene& s, glm::vec3 position, glm::vec3 target, float fovY, float nearPlane, float farPlane,
                 glm::vec3 up) {
  s.camera.position = position;
  s.camera.target = target;
  s.camera.up = up;
  s.camera.fovY = fovY;
  s.camera.near = nearPlane;
  s.camera.far = farPlane;
  s.hasCamera = true;
}

Scene smallStillLife(glm::vec3 offset, bool withLight) {
  Scene s;
  s.source = "test:small-still-life";
  const int plane = addMesh(s, makePlane(3.0f, 3.0f));
  const int cube = addMesh(s, makeCube(0.5f));
  const int sphere = addMesh(s, makeUvSphere(0.45f, 32, 16));
  addDraw(s, plane, addMaterial(s, {0.7f, 0.7f, 0.7f, 1.0f}, 0.0f, 0.8f), translate(offset), "floor");
  addDraw(s, cube, addMaterial(s, {0.8f, 0.35f, 0.2f, 1.0f}, 0.0f, 0.5f),
          glm::rotate(translate(offset + glm::vec3(-0.4f, 0.5f, -0.2f)), glm::radians(30.0f), glm::vec3(0, 1, 0)),
          "cube");
  addDraw(s, sphere, addMaterial(s, {0.25f, 0.5f, 0.85f, 1.0f}, 0.0f, 0.4f),
          translate(offset + glm::vec3(0.9f, 0.45f, 0.5f)), "sphere");
  if (withLight)
    s.pointLights.push_back(pointLight(offset + glm::vec3(0.6f, 1.4f, 1.3f), {1.0f, 0.9f, 0.8f}, 2.0f, 1.0f, 0.35f, 0.44f));
  s.ambient = glm::vec3(0.05f);
  placeCamera(s, offset + glm::vec3(0.0f, 2.0f, 3.6f), offset + glm::vec3(0.0f, 0.3f, 0.0f), 50.0f, 0.1f, 100.0f);
  return s;
}

}  // namespace rgraph::stab
