// Sampler states declared with slots (rgraph/sampler_state.h) change what a
// pass samples: a fullscreen pass reads a 4x4 texture of known texels through
// the config's "samplers" override, and the 8x8 result is compared exactly
// with the values GL's sampling rules give for each state.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "gl_test_util.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::test;

namespace {

constexpr Extent kOut{8, 8};  // the probe's output; the sampled texture is 4x4

// `src` (4x4 rgba32f, texel (x, y) = (x/4, y/4, 1, 1)) and a probe pass
// sampling it through `samplers` (the pass's "samplers" value, or "" for
// none) at uv * scale + offset (u_color), into `out` (the output, 8x8).
std::string pipeline(const std::string& samplers, const std::string& uvTransform = "[1, 1, 0, 0]") {
  return R"({
  "version": 1,
  "resources": {
    "src": { "format": "rgba32f", "size": [4, 4] },
    "out": { "format": "rgba32f", "size": "output" }
  },
  "passes": [
    { "name": "pattern", "type": "fullscreen", "params": { "shader": "sampler_pattern.frag" },
      "outputs": { "color": "src" } },
    { "name": "probe", "type": "fullscreen",
      "params": { "shader": "sampler_probe.frag", "color": )" + uvTransform + R"( },)" +
         (samplers.empty() ? std::string() : "\n      \"samplers\": { \"input0\": " + samplers + " },") + R"(
      "inputs": { "input0": "src" }, "outputs": { "color": "out" } }
  ],
  "output": "out"
})";
}

// Depth texels d(x, y) = (x + 64 y) / 4096 (depth_gradient.frag) compared
// with `ref` through `samplers` by sampler_shadow_probe.frag.
std::string shadowPipeline(const std::string& samplers, double ref) {
  return R"({
  "version": 1,
  "resources": {
    "grey": { "format": "rgba8", "size": [4, 4] },
    "depth": { "format": "depth32f", "size": [4, 4] },
    "out": { "format": "rgba32f", "size": "output" }
  },
  "passes": [
    { "name": "depth", "type": "fullscreen", "params": { "shader": "depth_gradient.frag" },
      "outputs": { "color": "grey", "depth": "depth" } },
    { "name": "probe", "type": "fullscreen",
      "params": { "shader": "sampler_shadow_probe.frag", "value": )" + std::to_string(ref) + R"( },
      "samplers": { "input0": )" + samplers + R"( },
      "inputs": { "input0": "depth" }, "outputs": { "color": "out" } }
  ],
  "output": "out"
})";
}

class SamplerStateTest : public GlTest {
 protected:
  // Renders one frame of `json`; the output as RGBA32F, rows bottom-up
  // (index (y * 8 + x) * 4 with y = 0 at the bottom, as gl_FragCoord).
  std::vector<float> render(const std::string& json) {
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(json, "sampler-test.json", diags);
    PipelineConfig cfg = doc.build(processRegistry(), diags);
    EXPECT_FALSE(hasErrors(diags)) << json;
    Executor exec(cfg, processRegistry(), *shaders);
    exec.resize(kOut);
    exec.renderFrame();
    // Every unit samples with its texture's parameters again after the pass.
    GLint sampler = -1;
    glGetIntegeri_v(GL_SAMPLER_BINDING, 0, &sampler);
    EXPECT_EQ(sampler, 0);
    std::vector<float> top = exec.readTextureRGBA32F("out");
    std::vector<float> rows(top.size());
    for (uint32_t y = 0; y < kOut.height; ++y)
      std::copy_n(top.begin() + (kOut.height - 1 - y) * kOut.width * 4, kOut.width * 4,
                  rows.begin() + y * kOut.width * 4);
    return rows;
  }
};

// Pixels whose red or green differs from want(x, y) (red, green), and the first.
size_t mismatches(const std::vector<float>& px, const std::function<std::array<double, 2>(uint32_t, uint32_t)>& want,
                  std::string* first) {
  size_t bad = 0;
  for (uint32_t y = 0; y < kOut.height; ++y)
    for (uint32_t x = 0; x < kOut.width; ++x) {
      const float* p = &px[(y * kOut.width + x) * 4];
      const std::array<double, 2> w = want(x, y);
      if (p[0] == static_cast<float>(w[0]) && p[1] == static_cast<float>(w[1])) continue;
      if (bad++ == 0 && first)
        *first = "(" + std::to_string(x) + ", " + std::to_string(y) + "): got " + std::to_string(p[0]) + ", " +
                 std::to_string(p[1]) + ", want " + std::to_string(w[0]) + ", " + std::to_string(w[1]);
    }
  return bad;
}

// Texel coordinate (in texels) of output pixel i's centre at uv * scale + offset.
double texelCoord(uint32_t i, double scale = 1.0, double offset = 0.0) {
  return ((i + 0.5) / 8.0 * scale + offset) * 4.0;
}
double nearestClamped(uint32_t i) { return std::floor(texelCoord(i)) * 0.25; }
// Linear: the two nearest texel centres weighted, clamped to the edge texels
// (the texel values grow linearly, so this is the coordinate clamped).
double linearClamped(uint32_t i) { return std::clamp(texelCoord(i) - 0.5, 0.0, 3.0) * 0.25; }

TEST_F(SamplerStateTest, NearestAndLinearFilterDiffer) {
  std::string first;
  const std::vector<float> nearest = render(pipeline(R"({ "filter": "nearest" })"));
  EXPECT_EQ(mismatches(nearest, [](uint32_t x, uint32_t y) { return std::array{nearestClamped(x), nearestClamped(y)}; },
                       &first), 0u) << first;
  const std::vector<float> linear = render(pipeline(R"({ "filter": "linear" })"));
  EXPECT_EQ(mismatches(linear, [](uint32_t x, uint32_t y) { return std::array{linearClamped(x), linearClamped(y)}; },
                       &first), 0u) << first;
  EXPECT_NE(nearest, linear);
  // No state: the texture's own parameters (linear, clamped), as before sampler states.
  EXPECT_EQ(render(pipeline("")), linear);
}

TEST_F(SamplerStateTest, ClampRepeatAndMirrorWrapDiffer) {
  // uv.x + 0.5: the right half of the output reads past the texture's edge.
  auto wrapped = [](uint32_t x, const std::function<double(double)>& wrap) {
    return std::floor(wrap(texelCoord(x, 1.0, 0.5))) * 0.25;
  };
  std::string first;
  const std::string shift = "[1, 1, 0.5, 0]";
  const std::vector<float> clamp = render(pipeline(R"({ "filter": "nearest", "wrap": "clamp" })", shift));
  EXPECT_EQ(mismatches(clamp, [&](uint32_t x, uint32_t y) {
    return std::array{wrapped(x, [](double t) { return std::min(t, 3.0); }), nearestClamped(y)};
  }, &first), 0u) << first;
  const std::vector<float> repeat = render(pipeline(R"({ "filter": "nearest", "wrap": "repeat" })", shift));
  EXPECT_EQ(mismatches(repeat, [&](uint32_t x, uint32_t y) {
    return std::array{wrapped(x, [](double t) { return std::fmod(t, 4.0); }), nearestClamped(y)};
  }, &first), 0u) << first;
  const std::vector<float> mirror = render(pipeline(R"({ "filter": "nearest", "wrap": "mirror" })", shift));
  EXPECT_EQ(mismatches(mirror, [&](uint32_t x, uint32_t y) {
    return std::array{wrapped(x, [](double t) { return t < 4.0 ? t : 8.0 - t; }), nearestClamped(y)};
  }, &first), 0u) << first;
  // Per axis: t repeats too, but v stays inside [0, 1), so only s matters.
  EXPECT_EQ(render(pipeline(R"({ "filter": "nearest", "wrap": { "s": "repeat", "t": "clamp" } })", shift)), repeat);
}

TEST_F(SamplerStateTest, BorderColourOutsideTheTexture) {
  const std::vector<float> px =
      render(pipeline(R"({ "filter": "nearest", "wrap": "border", "border": [0.125, 0.375, 0.625, 0.875] })",
                      "[1, 1, 0.5, 0]"));
  for (uint32_t y = 0; y < kOut.height; ++y)
    for (uint32_t x = 0; x < kOut.width; ++x) {
      const float* p = &px[(y * kOut.width + x) * 4];
      const bool outside = texelCoord(x, 1.0, 0.5) >= 4.0;
      const std::array<float, 4> want =
          outside ? std::array{0.125f, 0.375f, 0.625f, 0.875f}
                  : std::array{static_cast<float>(std::floor(texelCoord(x, 1.0, 0.5)) * 0.25),
                               static_cast<float>(nearestClamped(y)), 1.0f, 1.0f};
      EXPECT_EQ((std::array{p[0], p[1], p[2], p[3]}), want) << "at " << x << ", " << y;
    }
}

TEST_F(SamplerStateTest, DepthCompareModes) {
  const double ref = 65.5 / 4096.0;  // between texels (1, 1) and (2, 1)
  auto depth = [](uint32_t x, uint32_t y) { return (std::floor(texelCoord(x)) + 64.0 * std::floor(texelCoord(y))) / 4096.0; };
  std::string first;
  const std::vector<float> lessEqual = render(shadowPipeline(R"({ "filter": "nearest", "compare": "less_equal" })", ref));
  EXPECT_EQ(mismatches(lessEqual, [&](uint32_t x, uint32_t y) {
    const double v = ref <= depth(x, y) ? 1.0 : 0.0;
    return std::array{v, v};
  }, &first), 0u) << first;
  const std::vector<float> greater = render(shadowPipeline(R"({ "filter": "nearest", "compare": "greater" })", ref));
  EXPECT_EQ(mismatches(greater, [&](uint32_t x, uint32_t y) {
    const double v = ref > depth(x, y) ? 1.0 : 0.0;
    return std::array{v, v};
  }, &first), 0u) << first;
  // Both results occur, so the comparison really depends on the texel.
  EXPECT_NE(std::count(lessEqual.begin(), lessEqual.end(), 1.0f), 0);
  EXPECT_NE(std::count(lessEqual.begin(), lessEqual.end(), 0.0f), 0);
}

// A 64x64 texture of one-texel horizontal stripes at level 0 and their
// average (0.5) at every smaller level, sampled 8 texels a pixel across and
// one texel a pixel down (u_color = [1, 0.125, 0, 0]) through `state`.
std::string stripesPipeline(const std::string& state) {
  std::string levels;
  for (int k = 0; k <= 6; ++k)
    levels += R"(    { "name": "level)" + std::to_string(k) + R"(", "type": "fullscreen",
      "params": { "shader": "sampler_stripes.frag", "color": [)" + (k == 0 ? "0" : "0.5") + R"(, 0, 0, 0] },
      "outputs": { "color": "src.mip[)" + std::to_string(k) + R"(]" } },
)";
  return R"({
  "version": 1,
  "resources": {
    "src": { "format": "rgba32f", "size": [64, 64], "mips": "full" },
    "out": { "format": "rgba32f", "size": "output" }
  },
  "passes": [
)" + levels + R"(    { "name": "probe", "type": "fullscreen",
      "params": { "shader": "sampler_probe.frag", "color": [1, 0.125, 0, 0] },
      "samplers": { "input0": )" + state + R"( },
      "inputs": { "input0": "src" }, "outputs": { "color": "out" } }
  ],
  "output": "out"
})";
}

// Anisotropic filtering: the footprint is 8 texels long across the stripes'
// direction and 1 texel down. Trilinear picks the level of the long side
// (level 3: the average, 0.5, no stripe left); with anisotropy the level of
// the short side is sampled along the long one, so each odd row stays
// brighter than the even rows beside it. (How much contrast survives is the
// device's filter: llvmpipe's weights reach the neighbouring rows, 0.4 and
// 0.6; a box filter keeps 0 and 1.)
TEST_F(SamplerStateTest, AnisotropyKeepsDetailAlongTheShortSideOfTheFootprint) {
  float maxAniso = 1.0f;
  if (hasExtension("GL_ARB_texture_filter_anisotropic") || hasExtension("GL_EXT_texture_filter_anisotropic"))
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAniso);
  if (maxAniso < 8.0f) GTEST_SKIP() << "anisotropic filtering up to " << maxAniso << " only on this device";
  const std::vector<float> trilinear = render(stripesPipeline(R"({ "mip": "linear" })"));
  const std::vector<float> aniso = render(stripesPipeline(R"({ "mip": "linear", "anisotropy": 16 })"));
  auto red = [](const std::vector<float>& px, uint32_t x, uint32_t y) { return px[(y * kOut.width + x) * 4]; };
  double trilinearOff = 0.0, weakestStripe = 1.0;
  for (uint32_t y = 0; y < kOut.height; ++y)
    for (uint32_t x = 0; x < kOut.width; ++x) {
      trilinearOff = std::max(trilinearOff, std::abs(red(trilinear, x, y) - 0.5));
      if (y + 1 < kOut.height) {  // odd rows brighter than their even neighbours
        const double step = red(aniso, x, y + 1) - red(aniso, x, y);
        weakestStripe = std::min(weakestStripe, (y & 1) ? -step : step);
      }
    }
  EXPECT_LT(trilinearOff, 0.01) << "trilinear should see only the average";
  EXPECT_GT(weakestStripe, 0.1) << "anisotropic filtering should keep the stripes";
}

// One sampler object per distinct state, however many passes use it.
TEST_F(SamplerStateTest, OneSamplerObjectPerDistinctState) {
  const std::string json = R"({
  "version": 1,
  "resources": {
    "src": { "format": "rgba32f", "size": [4, 4] },
    "a": { "format": "rgba32f", "size": "output" },
    "b": { "format": "rgba32f", "size": "output" },
    "c": { "format": "rgba32f", "size": "output" }
  },
  "passes": [
    { "name": "pattern", "type": "fullscreen", "params": { "shader": "sampler_pattern.frag" },
      "outputs": { "color": "src" } },
    { "name": "p1", "type": "fullscreen", "params": { "shader": "sampler_probe.frag" },
      "samplers": { "input0": { "filter": "nearest" } }, "inputs": { "input0": "src" }, "outputs": { "color": "a" } },
    { "name": "p2", "type": "fullscreen", "params": { "shader": "sampler_probe.frag" },
      "samplers": { "input0": { "filter": "nearest" }, "input1": { "wrap": "mirror" } },
      "inputs": { "input0": "a", "input1": "src" }, "outputs": { "color": "b" } },
    { "name": "p3", "type": "fullscreen", "params": { "shader": "sampler_probe.frag" },
      "samplers": { "input0": { "wrap": "repeat" } }, "inputs": { "input0": "b" }, "outputs": { "color": "c" } }
  ],
  "output": "c"
})";
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(json, "cache.json", diags);
  PipelineConfig cfg = doc.build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags));
  const int64_t before = gl::createdObjects(gl::ObjectKind::sampler);
  Executor exec(cfg, processRegistry(), *shaders);
  exec.resize(kOut);
  exec.renderFrame();
  exec.renderFrame();
  // p1 and p2 share {nearest}; p2's input1 is not read by the shader (no
  // sampler made for it); p3 has its own.
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::sampler) - before, 2);
}

}  // namespace
