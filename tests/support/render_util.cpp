#include "render_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <glm/gtc/packing.hpp>

#include "rgraph/error.h"
#include "support/test_support.h"
#include "rgraph/image.h"
#include "rgraph/pipeline_load.h"

namespace rgraph::rtest {

GlContext& glContext() { return testsupport::sharedGlContext(); }

void RenderTest::SetUp() {
  try {
    glContext();
  } catch (const RuntimeError& e) {
    FAIL() << "no headless GL context: " << e.what();
  }
  shaders = std::make_unique<ShaderLibrary>();
  errorsAtStart = glContext().debugErrorCount();
}

void RenderTest::TearDown() {
  shaders.reset();
  if (testsupport::hasSharedGlContext()) {
    EXPECT_EQ(glContext().debugErrorCount(), errorsAtStart) << "GL debug errors, last: " << glContext().lastDebugError();
  }
}

std::string repoPath(const std::string& rel) { return std::string(RGRAPH_SOURCE_DIR) + "/" + rel; }
std::string testPipeline(const std::string& name) {
  return std::string(RGRAPH_TEST_DATA_DIR) + "/render/pipelines/" + name;
}
std::string assetPath(const std::string& rel) { return std::string(RGRAPH_ASSETS_DIR) + "/" + rel; }

PipelineConfig loadPipeline(const std::string& path) { return testsupport::loadPipelineOrThrow(path); }

void setParam(PipelineConfig& cfg, const std::string& pass, const std::string& key, ParamValue value) {
  for (size_t i = 0; i < cfg.graph.passes.size(); ++i) {
    if (cfg.graph.passes[i].name == pass) {
      cfg.params[i].set(key, std::move(value));
      return;
    }
  }
  throw RuntimeError("setParam: no pass named '" + pass + "' in " + cfg.file);
}

Image render(const PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders,
             const std::function<void(Executor&)>& inspect) {
  Executor exec(cfg, processRegistry(), shaders, &scene);
  exec.resize(size);
  exec.renderFrame();
  Image img;
  img.extent = exec.outputExtent();
  img.rgba = exec.readOutputRGBA8();
  if (inspect) inspect(exec);
  return img;
}

std::string pixelText(glm::ivec3 c) {
  return "(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

std::string ImageDiff::describe() const {
  if (worstX < 0) return "max abs diff 0";
  return "max abs diff " + std::to_string(maxDiff) + "/255 at pixel (" + std::to_string(worstX) + "," +
         std::to_string(worstRow) + "): " + pixelText(worstA) + " vs " + pixelText(worstB) + "; " +
         std::to_string(over) + " pixels over the tolerance";
}

ImageDiff compareImages(const Image& a, const Image& b, int tolerance) {
  ImageDiff d;
  if (a.extent != b.extent || a.rgba.size() != b.rgba.size()) {
    d.maxDiff = 255;
    d.over = static_cast<size_t>(-1);
    return d;
  }
  const ImageDifference diff = compareRGBA8(a.rgba, b.rgba);
  d.maxDiff = diff.maxAbs;
  d.over = diff.pixelsOver(tolerance);
  if (diff.maxAbs > 0) {
    d.worstX = static_cast<int>(diff.worstPixel % a.extent.width);
    d.worstRow = static_cast<int>(diff.worstPixel / a.extent.width);
    d.worstA = a.rgb(d.worstX, d.worstRow);
    d.worstB = b.rgb(d.worstX, d.worstRow);
  }
  return d;
}

double coverage(const Image& img, glm::ivec3 background, int tolerance) {
  size_t n = 0;
  const size_t total = static_cast<size_t>(img.extent.width) * img.extent.height;
  for (int row = 0; row < static_cast<int>(img.extent.height); ++row)
    for (int x = 0; x < static_cast<int>(img.extent.width); ++x) {
      const glm::ivec3 d = glm::abs(img.rgb(x, row) - background);
      if (std::max({d.r, d.g, d.b}) > tolerance) ++n;
    }
  return total ? static_cast<double>(n) / static_cast<double>(total) : 0.0;
}

Scene ambientOnly(const Scene& scene) {
  Scene s = scene;
  s.pointLights.clear();
  s.directionalLights.clear();
  return s;
}

std::string LightGain::describe() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%zu of %zu pixels (%.1f%%) brighter than the ambient-only frame, largest gain %d/255",
                brighter, pixels, share() * 100.0, maxGain);
  return buf;
}

LightGain lightGain(const std::vector<uint8_t>& lit, const std::vector<uint8_t>& ambient, int minGain) {
  LightGain g;
  if (lit.size() != ambient.size()) return g;  // nothing brighter: the caller's expectation fails
  g.pixels = lit.size() / 4;
  for (size_t i = 0; i + 3 < lit.size(); i += 4) {
    int gain = 0;
    for (size_t c = 0; c < 3; ++c) gain = std::max(gain, int(lit[i + c]) - int(ambient[i + c]));
    g.maxGain = std::max(g.maxGain, gain);
    g.brighter += gain >= minGain;
  }
  return g;
}

LightGain expectLightsShow(const Image& lit, const PipelineConfig& cfg, const Scene& scene, ShaderLibrary& shaders,
                           double minShare, const std::string& name) {
  const Image ambient = render(cfg, ambientOnly(scene), lit.extent, shaders);
  const LightGain g = lightGain(lit, ambient, kMinLightGain);
  std::printf("[ measure  ] %s: %s\n", name.c_str(), g.describe().c_str());
  EXPECT_GE(g.share(), minShare) << name << ": the lights do not show: " << g.describe() << "; images "
                                 << saveImage(lit, name + "-lit") << ", " << saveImage(ambient, name + "-ambient");
  return g;
}

std::string saveImage(const Image& img, const std::string& name) {
  const char* env = std::getenv("RGRAPH_TEST_OUTPUT");
  const std::filesystem::path dir =
      env && *env ? std::filesystem::path(env) : std::filesystem::temp_directory_path() / "rgraph-render-tests";
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string path = (dir / (name + ".png")).string();
  try {
    writePng(path, img.extent.width, img.extent.height, img.rgba);
  } catch (const RuntimeError&) {
    return "(could not write " + path + ")";
  }
  return path;
}

// ---------------------------------------------------------------- camera maths

namespace {
glm::dmat4 viewProj(const Camera& cam, Extent size) {
  const double aspect = static_cast<double>(size.width) / static_cast<double>(size.height);
  return glm::dmat4(cam.projection(static_cast<float>(aspect))) * glm::dmat4(cam.view());
}
}  // namespace

Ray pixelRay(const Camera& cam, Extent size, int x, int row) {
  const glm::dmat4 inv = glm::inverse(viewProj(cam, size));
  const double ndcX = (x + 0.5) / size.width * 2.0 - 1.0;
  const double ndcY = 1.0 - (row + 0.5) / size.height * 2.0;
  glm::dvec4 nearP = inv * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
  glm::dvec4 farP = inv * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
  nearP /= nearP.w;
  farP /= farP.w;
  Ray r;
  r.origin = glm::dvec3(cam.position);
  r.dir = glm::normalize(glm::dvec3(farP) - glm::dvec3(nearP));
  return r;
}

std::optional<ScreenPoint> project(const Camera& cam, Extent size, glm::dvec3 world) {
  const glm::dvec4 clip = viewProj(cam, size) * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0) return std::nullopt;
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  ScreenPoint p;
  p.x = (ndc.x * 0.5 + 0.5) * size.width;
  p.row = (0.5 - ndc.y * 0.5) * size.height;
  p.depth = glm::dot(world - glm::dvec3(cam.position), glm::dvec3(cam.forward()));
  return p;
}

std::optional<double> hitBox(const Ray& r, glm::dvec3 bmin, glm::dvec3 bmax) {
  double t0 = 0.0, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(r.dir[a]) < 1e-300) {
      if (r.origin[a] < bmin[a] || r.origin[a] > bmax[a]) return std::nullopt;
      continue;
    }
    double ta = (bmin[a] - r.origin[a]) / r.dir[a], tb = (bmax[a] - r.origin[a]) / r.dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return std::nullopt;
  }
  return t0 > 0.0 ? std::optional<double>(t0) : std::nullopt;
}

std::optional<double> hitSphere(const Ray& r, glm::dvec3 centre, double radius) {
  const glm::dvec3 oc = r.origin - centre;
  const double b = glm::dot(oc, r.dir);
  const double c = glm::dot(oc, oc) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  if (-b - s > 0.0) return -b - s;
  if (-b + s > 0.0) return -b + s;
  return std::nullopt;
}

float toHalf(float v) { return glm::unpackHalf1x16(glm::packHalf1x16(v)); }

}  // namespace rgraph::rtest
