// Helpers of the image tests (deferred shading end to end): one headless GL
// context per test program, pipelines loaded from JSON with parameters
// overridden per test, images rendered and compared, and the camera maths the
// tests use to know where things land on screen (rays through pixel centres,
// analytic ray casts against boxes and spheres).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/graph.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace rgraph::rtest {

// The process-wide headless context (created on first use).
GlContext& glContext();

// Fixture: a fresh ShaderLibrary per test; fails the test when it caused GL
// debug errors.
class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  std::unique_ptr<ShaderLibrary> shaders;
  uint64_t errorsAtStart = 0;
};

// Paths.
std::string repoPath(const std::string& rel);       // <repo>/rel
std::string testPipeline(const std::string& name);  // tests/render/pipelines/<name>
std::string assetPath(const std::string& rel);      // ../shared/assets/<rel>

// Loads and builds a pipeline config with the built-in pass types; throws
// RuntimeError with every diagnostic when it has errors.
PipelineConfig loadPipeline(const std::string& path);
// Overrides one parameter of the pass named `pass` (throws when there is no such pass).
void setParam(PipelineConfig& cfg, const std::string& pass, const std::string& key, ParamValue value);

// An RGBA8 image, rows top-down.
struct Image {
  Extent extent;
  std::vector<uint8_t> rgba;
  const uint8_t* at(int x, int row) const { return &rgba[(static_cast<size_t>(row) * extent.width + x) * 4]; }
  glm::ivec3 rgb(int x, int row) const {
    const uint8_t* p = at(x, row);
    return {p[0], p[1], p[2]};
  }
};

// Renders one frame of `cfg` with `scene` at `size` and reads the output back.
// `inspect`, when given, runs after the frame with the executor (read other
// targets there).
Image render(const PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders,
             const std::function<void(Executor&)>& inspect = {});

struct ImageDiff {
  int maxDiff = 0;          // max over pixels and RGB channels of |a - b|
  size_t over = 0;          // pixels with some channel differing by more than the tolerance
  int worstX = -1, worstRow = -1;
  glm::ivec3 worstA{0}, worstB{0};
  std::string describe() const;
};
ImageDiff compareImages(const Image& a, const Image& b, int tolerance);
// Share of pixels whose RGB differs from `background` by more than `tolerance`.
double coverage(const Image& img, glm::ivec3 background, int tolerance = 2);

// ---------------------------------------------------------------- lit against ambient-only

// The same scene lit by ambient light only: every point and directional light
// removed (camera, geometry, materials and ambient unchanged). A renderer that
// drops its lights produces this frame; a lit frame must exceed it where the
// lights reach.
Scene ambientOnly(const Scene& scene);

// How far a lit frame rises above the ambient-only frame of the same scene
// through the same pipeline: pixels whose brightest channel gained at least
// `minGain`/255 (a black frame gains nothing and loses the ambient; an
// ambient-only frame gains nothing).
struct LightGain {
  size_t brighter = 0;  // pixels with some channel at least minGain above the ambient frame
  size_t pixels = 0;
  int maxGain = 0;      // largest per-channel gain over all pixels
  double share() const { return pixels ? static_cast<double>(brighter) / static_cast<double>(pixels) : 0.0; }
  std::string describe() const;
};
LightGain lightGain(const std::vector<uint8_t>& litRgba, const std::vector<uint8_t>& ambientRgba, int minGain);
inline LightGain lightGain(const Image& lit, const Image& ambient, int minGain) {
  return lightGain(lit.rgba, ambient.rgba, minGain);
}
// 8/255: the lit and ambient-only frames differ only by their lights, so a
// pixel no light reaches differs by 0 (same pipeline, same rasterisation); a
// light reaching a surface adds tens of levels.
constexpr int kMinLightGain = 8;
// The guard of a comparison test: renders `cfg` with ambientOnly(scene) at
// `lit`'s size and expects `lit` kMinLightGain brighter on at least
// `minShare` of the pixels (prints the measure, saves both images when not).
// A black or ambient-only frame gains on 0% of its pixels; the comparison
// tests pass 0.05 where they measure 8.8% (the LearnOpenGL scene's dim lights
// under Cook-Torrance) to 75%.
LightGain expectLightsShow(const Image& lit, const PipelineConfig& cfg, const Scene& scene, ShaderLibrary& shaders,
                           double minShare, const std::string& name);

// Writes a PNG under $RGRAPH_TEST_OUTPUT (default: <temp dir>/rgraph-render-tests)
// for looking at failures; returns the path. scripts/gpu-check.sh collects them.
std::string saveImage(const Image& img, const std::string& name);
std::string pixelText(glm::ivec3 c);

// ---------------------------------------------------------------- camera maths (double precision)

struct Ray {
  glm::dvec3 origin, dir;  // dir unit length
};
// The ray from the camera through the centre of pixel (x, row) (row 0 at the top).
Ray pixelRay(const Camera& cam, Extent size, int x, int row);
// Where a world point lands: x and row in pixels (pixel centres at +0.5),
// and its view depth (distance along the view direction). nullopt when behind the camera.
struct ScreenPoint {
  double x, row, depth;
  int px() const { return static_cast<int>(std::floor(x)); }
  int prow() const { return static_cast<int>(std::floor(row)); }
};
std::optional<ScreenPoint> project(const Camera& cam, Extent size, glm::dvec3 world);

// Ray parameter of the first hit with an axis-aligned box / sphere (t > 0), or nullopt.
std::optional<double> hitBox(const Ray& r, glm::dvec3 bmin, glm::dvec3 bmax);
std::optional<double> hitSphere(const Ray& r, glm::dvec3 centre, double radius);

// Half-float rounding of a float (round to nearest even), for rgba16f expectations.
float toHalf(float v);

}  // namespace rgraph::rtest
