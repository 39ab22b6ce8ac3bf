// Cascaded shadow maps where they fail (issue 28), measured and bounded:
// shimmering (a camera sliding by sub-texel steps moves the edges of static
// shadows when the cascades are fitted tightly each frame; stabilised ones
// stand still) and seams (the light one surface point gets from the cascades
// either side of a split boundary). Each figure is printed ([ measure ]).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "rgraph/gl/executor.h"
#include "rgraph/pipeline_load.h"
#include "shadow_probe.h"

namespace {
using namespace rgraph;
using shadows::LightKind;
using shadowtest::ProbeOptions;
using shadowtest::ProbeResult;

class ShadowCascades : public rtest::RenderTest {};

// One executor of a pipeline document, adapted once to the scene, rendering
// frame after frame with a moving camera: the cascades follow the camera
// every frame without a rebuild, as in the Renderer.
class Frames {
 public:
  Frames(const nlohmann::json& doc, const Scene& scene, Extent size) : scene_(scene), size_(size) {
    cfg_ = testsupport::buildPipelineOrThrow(doc.dump(), "deferred-pbr-shadows.json (test)");
    adaptToScene(cfg_, processRegistry(),
                 sceneFeatures(scene_, scene_.camera, float(size.width) / float(size.height)));
    exec_ = std::make_unique<Executor>(cfg_, processRegistry(), shaders_, &scene_);
    exec_->resize(size);
  }
  rtest::Image render(const Camera& camera) {
    exec_->setCamera(camera);
    exec_->renderFrame();
    rtest::Image img;
    img.extent = exec_->outputExtent();
    img.rgba = exec_->readOutputRGBA8();
    return img;
  }

 private:
  Scene scene_;
  Extent size_;
  PipelineConfig cfg_;
  ShaderLibrary shaders_;
  std::unique_ptr<Executor> exec_;
};

nlohmann::json withShadowParams(nlohmann::json doc, const nlohmann::json& params) {
  for (auto& pass : doc["passes"])
    if (pass["type"] == "shadow_map") pass["params"].update(params);
  return doc;
}

int brightest(const rtest::Image& img, int x, int row) {
  const glm::ivec3 c = img.rgb(x, row);
  return std::max({c.r, c.g, c.b});
}

// The image's brightest channel at window position (x, y) (y up, pixel
// centres at +0.5), bilinear between pixel centres: a smooth field that a
// world point can be read from whatever the pixel grid's phase.
double bilinear(const rtest::Image& img, double x, double y) {
  const double fx = x - 0.5, fy = double(img.extent.height) - y - 0.5;  // rows run top down
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const double tx = fx - x0, ty = fy - y0;
  auto at = [&](int px, int py) { return double(brightest(img, px, py)); };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) + ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

// Shimmering, in world space: the camera slides sideways by a tenth of a
// texel (of the cascade the view's target lies in) per frame for 32 frames
// over static casters under the sun, 3x3 PCF, maps of 256^2 (about 2.5
// pixels a texel at 480x360). The shadow a fixed floor point gets is read
// from each frame (shadowed over unshadowed image, bilinear at the point's
// projection); the figure is the mean change of that visibility from frame
// to frame over the points inside a penumbra in some frame and seen by the
// camera in all. Stabilised maps keep every point's texel, so only the
// images' resampling moves it; maps fitted tightly each frame slide under
// the casters and the penumbrae crawl.
double shimmer(bool stabilize) {
  Scene scene = shadowtest::testScene();
  scene.directionalLights.push_back(shadowtest::sun());
  const nlohmann::json params = {{"size", 256}, {"stabilize", stabilize}};
  const Extent size{480, 360};
  const float aspect = float(size.width) / float(size.height);
  Frames on(withShadowParams(shadowtest::pipelineDoc("pcf"), params), scene, size);
  Frames off(withShadowParams(shadowtest::pipelineDoc(""), params), scene, size);
  shadows::ShadowSettings s;
  s.resolution = 256;
  const auto views = shadows::shadowViews(scene, scene.camera, aspect, s, {{LightKind::directional, 0, 0, 4}});
  const float targetDepth = glm::length(scene.camera.target - scene.camera.position);
  float texel = views.back().texelWorld;
  for (const auto& v : views)
    if (targetDepth >= v.splitNear && targetDepth < v.splitFar) texel = v.texelWorld;
  const float step = 0.1f * texel;
  const glm::vec3 side = glm::normalize(glm::cross(scene.camera.target - scene.camera.position, glm::vec3(0, 1, 0)));
  const int frames = 32;
  std::vector<Camera> cameras;
  for (int f = 0; f <= frames; ++f) {
    Camera cam = scene.camera;
    cam.position += side * (step * float(f));
    cam.target += side * (step * float(f));
    cameras.push_back(cam);
  }
  // Floor points every 0.02 units, seen from every camera (a point light at
  // the eye lights them) and inside every frame's image.
  const oracle::VisibilityOracle exact(scene);
  std::vector<glm::vec3> points;
  for (float z = -5.0f; z <= 5.0f; z += 0.02f)
    for (float x = -5.0f; x <= 5.0f; x += 0.02f) {
      const glm::vec3 p(x, 0.0f, z);
      bool seen = true;
      for (int f : {0, frames}) {
        PointLight eye;
        eye.position = cameras[size_t(f)].position;
        eye.radius = 1e6f;
        seen = seen && exact.classify(oracle::VisibilityOracle::Probe{glm::dvec3(p), {0.0, 1.0, 0.0}}, eye) ==
                           oracle::Visibility::lit;
      }
      if (seen) points.push_back(p);
    }
  std::vector<std::vector<double>> visibility(points.size());
  std::vector<bool> inside(points.size(), true);
  for (int f = 0; f <= frames; ++f) {
    const rtest::Image imgOn = on.render(cameras[size_t(f)]), imgOff = off.render(cameras[size_t(f)]);
    const glm::mat4 vp = cameras[size_t(f)].viewProjection(aspect);
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::vec4 clip = vp * glm::vec4(points[i], 1.0f);
      const double x = (clip.x / clip.w * 0.5 + 0.5) * size.width, y = (clip.y / clip.w * 0.5 + 0.5) * size.height;
      if (clip.w <= 0.0f || x < 2 || y < 2 || x > size.width - 2 || y > size.height - 2) {
        inside[i] = false;
        continue;
      }
      const double lit = bilinear(imgOff, x, y);
      if (lit < 24.0) inside[i] = false;
      visibility[i].push_back(std::min(1.0, bilinear(imgOn, x, y) / std::max(lit, 1.0)));
    }
  }
  double change = 0.0;
  long samples = 0, penumbra = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!inside[i]) continue;
    const auto& v = visibility[i];
    if (!std::any_of(v.begin(), v.end(), [](double a) { return a > 0.05 && a < 0.95; })) continue;
    ++penumbra;
    for (size_t f = 1; f < v.size(); ++f) change += std::abs(v[f] - v[f - 1]), ++samples;
  }
  const double mean = samples ? change / double(samples) : 0.0;
  std::printf("[ measure  ] shimmer, %s cascades: mean visibility change %.4f per frame at %ld floor points in a "
              "penumbra (of %zu seen), 32 frames, camera step %.5f units (a tenth of a texel)\n",
              stabilize ? "stabilised" : "tight", mean, penumbra, points.size(), step);
  EXPECT_GE(penumbra, 2000) << "the points should cover shadow edges";
  return mean;
}

TEST_F(ShadowCascades, StabilisedCascadesDoNotShimmerWhenTheCameraSlides) {
  const double stable = shimmer(true);
  const double tight = shimmer(false);
  EXPECT_LE(stable, 0.01);
  EXPECT_GE(tight, 3.0 * stable) << "tight cascades should crawl: the measure sees it";
}

// Posts in a row across the view under a sun from behind them, so that their
// shadows run away from the camera across the split between cascades.
Scene seamScene() {
  Scene scene = shadowtest::testScene();
  scene.primitives.resize(1);  // the floor
  for (int i = -9; i <= 9; ++i) shadowtest::addBox(scene, {1.1f * float(i), 1.0f, 4.5f}, {0.15f, 1.0f, 0.15f});
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.15f, -0.6f, -0.8f));
  sun.intensity = 1.5f;
  scene.directionalLights.push_back(sun);
  return scene;
}

struct Seams {
  int pairs = 0, mismatched = 0, probes = 0, agree = 0;
  double sumDiff = 0.0, maxDiff = 0.0;
};

// Seams: vertically adjacent probes (two pixels apart) that lie in different
// cascades, neither near a shadow edge (2.5 texels of its own cascade) and on
// the same side of the exact shadow: the difference of their light (1: fully
// lit) should be nothing. Also the agreement with exact visibility of every
// probe within 3 of those pairs' rows.
Seams seams(const std::string& filter, const nlohmann::json& params, const std::string& name) {
  const Scene scene = seamScene();
  ProbeOptions o;
  o.filter = filter;
  o.edit = [&](nlohmann::json& doc) { doc = withShadowParams(doc, params); };
  shadows::ShadowSettings s;
  s.resolution = shadowtest::kMapSize;
  if (params.contains("lambda")) s.lambda = params["lambda"].get<float>();
  const auto views = shadows::shadowViews(scene, scene.camera, float(o.size.width) / float(o.size.height), s,
                                          {{LightKind::directional, 0, 0, 4}});
  const glm::dvec3 eye(scene.camera.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(scene.camera.target - scene.camera.position));
  auto cascadeOf = [&](const glm::dvec3& p) {
    const double depth = glm::dot(p - eye, forward);
    for (const auto& v : views)
      if (depth >= v.splitNear && depth < v.splitFar) return int(v.cascade);
    return -1;
  };
  std::map<std::pair<int, int>, ProbeResult> probes;
  shadowtest::forEachProbe(scene, scene.directionalLights[0], {LightKind::directional, 0, 0, 4}, o,
                           [&](const ProbeResult& r) { probes[{r.x, r.row}] = r; }, "shadow-" + name);
  Seams out;
  std::map<std::pair<int, int>, bool> nearSeam;
  for (const auto& [at, a] : probes) {
    const auto below = probes.find({at.first, at.second + 2});
    if (below == probes.end()) continue;
    const ProbeResult& b = below->second;
    if (cascadeOf(a.probe.point) == cascadeOf(b.probe.point)) continue;
    for (int dr = -6; dr <= 8; dr += 2) nearSeam[{at.first, at.second + dr}] = true;
    if (a.nearEdge || b.nearEdge || a.exact != b.exact) continue;
    const double d = std::abs(std::min(a.lightLevel, 1.0) - std::min(b.lightLevel, 1.0));
    ++out.pairs;
    out.sumDiff += d;
    out.maxDiff = std::max(out.maxDiff, d);
    out.mismatched += a.mapShadowed != b.mapShadowed;
  }
  for (const auto& [at, r] : probes) {
    if (!nearSeam.count(at) || r.nearEdge) continue;
    ++out.probes;
    out.agree += r.mapShadowed == (r.exact == oracle::Visibility::shadowed);
  }
  std::printf("[ measure  ] cascade seams, %s: %d probe pairs across a split, %d shadowed on one side only, light "
              "difference mean %.4f max %.4f; %d probes near the splits, %.3f%% agree with exact visibility\n",
              name.c_str(), out.pairs, out.mismatched, out.pairs ? out.sumDiff / out.pairs : 0.0, out.maxDiff,
              out.probes, out.probes ? 100.0 * out.agree / out.probes : 0.0);
  return out;
}

TEST_F(ShadowCascades, SplitBoundariesShowNoSeam) {
  for (const char* filter : {"hard", "pcf"}) {
    const Seams s = seams(filter, nlohmann::json::object(), std::string("seams-") + filter);
    EXPECT_GE(s.pairs, 100) << filter << ": the probes should cross a split";
    EXPECT_LE(s.mismatched, s.pairs / 200) << filter;
    EXPECT_LE(s.sumDiff / std::max(s.pairs, 1), 0.01) << filter;
    EXPECT_GE(s.agree, s.probes * 995 / 1000) << filter;
  }
}

}  // namespace
