// The bloom plugin's defining properties against a double-precision oracle
// written from its documented definition (plugins/bloom/bloom.cpp):
//   bright    = c * max(soft, b - t) / b, b = max channel, soft the quadratic
//               knee (b - t + k)^2 / 4k on t - k < b < t + k; at half size a
//               2x2 box average first;
//   blur      = `iterations` times a horizontal then a vertical 9-tap filter
//               with taps `radius` texels apart, weights the binomial
//               coefficients C(12, 6 + i), i = -4..4, over their sum 4070
//               (LearnOpenGL's Gaussian; 4096 - 2 * (1 + 12 + 66) = 4070);
//   composite = hdr + intensity * bloom (bilinear upsampling when smaller).
// So one bright pixel of value V on black adds intensity * (V - t) *
// K(dx) * K(dy), K = the 1D kernel convolved with itself `iterations` times:
// energy intensity * (V - t), variance iterations * radius^2 * sum(i^2 w_i)
// per axis, nothing beyond 4 * iterations * radius texels.
//
// Every target is rgba32f, at full size unless stated, so the blur taps land
// on texel centres. Tolerances:
//   sums (energy)  1e-5 relative: fp32 rounding of a few dozen operations per
//                  pixel (2^-24 each) summed over the image; measured 1e-7;
//   per pixel      2e-5 of the peak: the bright and composite passes sample
//                  with bilinear filtering at the interpolated v_uv, a few
//                  1e-6 texels off the centre, so a one-pixel image leaks that
//                  fraction to its neighbours per pass and axis; measured
//                  5.2e-6 (at the peak), arithmetic alone ~1e-7;
//   below the threshold and beyond the kernel's reach: exact.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "plugin_oracle.h"

using namespace rgraph;
using namespace rgraph::poracle;

namespace {

constexpr int kSize = 64;
constexpr double kRel = 1e-5;       // sums, and uniform frames (no filtering error there)
constexpr double kPixelRel = 2e-5;  // per pixel of a one-pixel image, of its peak

struct Bloom {
  std::string scale = "1.0";  // size of the bright and blur targets
  double threshold = 1.0, knee = 0.0, intensity = 0.5, radius = 1.0;
  int iterations = 3;
  int mode = 0;  // oracle_frame.frag: 0 one pixel, 1 uniform, 2 ramp
  double value = 10.0;
  int px = 32, py = 32;  // the bright pixel, GL window coordinates
};

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// (unformatted: the config reads as JSON)
// clang-format off
std::string config(const Bloom& b) {
  return R"({
    "version": 1,
    "resources": {
      "hdr":    { "format": "rgba32f" },
      "bright": { "format": "rgba32f", "size": { "scale": )" + b.scale + R"( } },
      "blur_a": { "format": "rgba32f", "size": { "scale": )" + b.scale + R"( } },
      "blur_b": { "format": "rgba32f", "size": { "scale": )" + b.scale + R"( } },
      "out":    { "format": "rgba32f" }
    },
    "passes": [
      { "name": "frame", "type": "fullscreen",
        "params": { "shader": "oracle_frame.frag", "value": )" + num(b.value) + R"(,
                    "color": [)" + std::to_string(b.px) + ", " + std::to_string(b.py) + ", " + std::to_string(b.mode) +
         R"(, 0] },
        "outputs": { "color": "hdr" } },
      { "name": "bright", "type": "bloom_bright",
        "params": { "threshold": )" + num(b.threshold) + R"(, "knee": )" + num(b.knee) + R"( },
        "inputs": { "hdr": "hdr" }, "outputs": { "bright": "bright" } },
      { "name": "blur", "type": "bloom_blur",
        "params": { "iterations": )" + std::to_string(b.iterations) + R"(, "radius": )" + num(b.radius) + R"( },
        "inputs": { "src": "bright" }, "outputs": { "dst": "blur_a", "temp": "blur_b" } },
      { "name": "composite", "type": "bloom_composite", "params": { "intensity": )" + num(b.intensity) + R"( },
        "inputs": { "hdr": "hdr", "bloom": "blur_a" }, "outputs": { "color": "out" } }
    ],
    "output": "out"
  })";
}
// clang-format on

// The 9 tap weights from their definition: C(12, 6 + i) / 4070.
std::vector<double> tapWeights() {
  std::vector<double> w;
  for (int i = -4; i <= 4; ++i) {
    double c = 1.0;
    for (int j = 1; j <= 6 + i; ++j) c = c * (12 - j + 1) / j;
    w.push_back(c / 4070.0);
  }
  return w;
}

// The 1D kernel after `iterations` passes, taps `radius` (an integer) texels
// apart; index = offset + half width.
std::vector<double> kernel1d(int iterations, int radius) {
  const std::vector<double> w = tapWeights();
  std::vector<double> k = {1.0};
  for (int it = 0; it < iterations; ++it) {
    std::vector<double> next(k.size() + 8 * static_cast<size_t>(radius), 0.0);
    for (size_t a = 0; a < k.size(); ++a)
      for (size_t t = 0; t < w.size(); ++t) next[a + t * static_cast<size_t>(radius)] += k[a] * w[t];
    k = std::move(next);
  }
  return k;
}

// The bloom added to the frame: out - hdr.
Plane added(const std::map<std::string, Plane>& r) {
  Plane d = r.at("out");
  const Plane& in = r.at("hdr");
  for (size_t i = 0; i < d.v.size(); ++i) d.v[i] -= in.v[i];
  return d;
}

double sum(const Plane& p) {
  double s = 0.0;
  for (double v : p.v) s += v;
  return s;
}

class OracleBloom : public PluginOracleTest {
 protected:
  // The red channel of the input frame ("hdr") and of the result ("out"); the frames are grey.
  std::map<std::string, Plane> run(const Bloom& b) {
    std::map<std::string, Plane> red;
    for (auto& [name, img] : render(config(b), {kSize, kSize}, {"hdr", "out"})) red[name] = img.c[0];
    return red;
  }
};

}  // namespace

// Every pixel of one bright pixel's bloom is intensity * (V - t) * K(dx) K(dy).
TEST_F(OracleBloom, SinglePixelSpreadsAsTheSeparableKernel) {
  for (int radius : {1, 2}) {
    Bloom b;
    b.radius = radius;
    b.iterations = radius == 1 ? 3 : 2;
    const auto r = run(b);
    const Plane d = added(r);
    const std::vector<double> k = kernel1d(b.iterations, radius);
    const int half = static_cast<int>(k.size() / 2);
    const int cx = b.px, crow = kSize - 1 - b.py;  // rows top-down
    ASSERT_EQ(r.at("hdr").at(cx, crow), b.value) << "the bright pixel is not where the test put it";
    const double scale = b.intensity * (b.value - b.threshold);
    const double peak = scale * k[half] * k[half];
    double worst = 0.0;
    int worstDx = 0, worstDy = 0;
    for (int row = 0; row < kSize; ++row)
      for (int x = 0; x < kSize; ++x) {
        const int dx = x - cx, dy = row - crow;
        const bool inside = std::abs(dx) <= half && std::abs(dy) <= half;
        const double want = inside ? scale * k[dx + half] * k[dy + half] : 0.0;
        const double got = d.at(x, row);
        if (!inside) {
          ASSERT_EQ(got, 0.0) << "light beyond the kernel's reach (" << half << " texels) at dx " << dx << " dy " << dy
                              << ", radius " << radius;
          continue;
        }
        if (std::abs(got - want) / peak > worst) {
          worst = std::abs(got - want) / peak;
          worstDx = dx, worstDy = dy;
        }
        ASSERT_NEAR(got, want, kPixelRel * peak) << "dx " << dx << " dy " << dy << ", radius " << radius;
      }
    // The kernel's reach is exactly 4 * iterations * radius texels: the last ring is lit.
    EXPECT_GT(d.at(cx + half, crow), 0.0);
    EXPECT_GT(d.at(cx, crow - half), 0.0);
    std::printf("radius %d iterations %d: reach %d texels, worst |error| / peak %.2e at dx %d dy %d\n", radius,
                b.iterations, half, worst, worstDx, worstDy);
  }
}

// The blur's weights sum to 1: the added energy is intensity times the energy above the threshold.
TEST_F(OracleBloom, ConservesTheEnergyAboveTheThreshold) {
  for (double intensity : {0.5, 1.0, 2.0}) {
    Bloom b;
    b.intensity = intensity;
    const double got = sum(added(run(b)));
    const double want = intensity * (b.value - b.threshold);
    EXPECT_NEAR(got, want, kRel * want) << "intensity " << intensity;
    std::printf("intensity %.1f: added energy %.7f, expected %.7f\n", intensity, got, want);
  }
}

// Half-size bright and blur targets: the bright pass averages 2x2 texels
// before thresholding, the composite's bilinear upsampling spreads each
// half-size texel over 4 full-size pixels: added = intensity * 4 * (V/4 - t).
TEST_F(OracleBloom, HalfSizeDownsamplesBeforeTheThreshold) {
  Bloom b;
  b.scale = "0.5";
  b.value = 40.0;
  b.intensity = 1.0;
  const double got = sum(added(run(b)));
  const double want = b.intensity * 4.0 * (b.value / 4.0 - b.threshold);
  EXPECT_NEAR(got, want, kRel * want);
  std::printf("half size: added energy %.6f, expected %.6f\n", got, want);
}

// Second moments along x and y: iterations * radius^2 * sum(i^2 w_i) (2.854 for one pass);
// the spot is symmetric in x, in y and under the swap of x and y, and centred on the pixel.
TEST_F(OracleBloom, SpotIsSymmetricCentredAndAsWideAsTheKernel) {
  const std::vector<double> w = tapWeights();
  double var1 = 0.0;
  for (int i = -4; i <= 4; ++i) var1 += i * i * w[static_cast<size_t>(i + 4)];
  for (int radius : {1, 2}) {
    Bloom b;
    b.radius = radius;
    b.iterations = 2;
    const Plane d = added(run(b));
    const int cx = b.px, crow = kSize - 1 - b.py;
    const double peak = d.at(cx, crow);
    double e = 0.0, mx = 0.0, my = 0.0, vx = 0.0, vy = 0.0, asym = 0.0;
    for (int row = 0; row < kSize; ++row)
      for (int x = 0; x < kSize; ++x) {
        const double v = d.at(x, row);
        const int dx = x - cx, dy = row - crow;
        e += v;
        mx += v * dx, my += v * dy, vx += v * dx * dx, vy += v * dy * dy;
        if (std::abs(dx) < 20 && std::abs(dy) < 20) {
          asym = std::max(asym, std::abs(v - d.at(cx - dx, row)));
          asym = std::max(asym, std::abs(v - d.at(x, crow - dy)));
          asym = std::max(asym, std::abs(v - d.at(cx + dy, crow + dx)));
        }
      }
    const double want = b.iterations * radius * radius * var1;
    EXPECT_NEAR(mx / e, 0.0, 1e-4) << "not centred in x";
    EXPECT_NEAR(my / e, 0.0, 1e-4) << "not centred in y";
    EXPECT_NEAR(vx / e, want, kRel * want * 10) << "radius " << radius;
    EXPECT_NEAR(vy / e, want, kRel * want * 10) << "radius " << radius;
    EXPECT_LE(asym, kPixelRel * peak) << "not symmetric";
    std::printf("radius %d: variance x %.6f y %.6f expected %.6f; asymmetry / peak %.1e\n", radius, vx / e, vy / e,
                want, asym / peak);
  }
}

// Nothing above the threshold (below t - knee with a soft knee, up to t with
// a hard one): the frame comes out bit for bit as it went in.
TEST_F(OracleBloom, FrameBelowTheThresholdIsUnchanged) {
  for (double knee : {0.0, 0.5}) {
    Bloom b;
    b.mode = 2;
    b.knee = knee;
    b.intensity = 4.0;
    b.value = b.threshold - knee;
    const auto r = run(b);
    const Plane& in = r.at("hdr");
    const Plane& out = r.at("out");
    EXPECT_EQ(*std::max_element(in.v.begin(), in.v.end()), b.value) << "the ramp must reach t - knee";
    size_t changed = 0;
    for (size_t i = 0; i < in.v.size(); ++i) changed += out.v[i] != in.v[i] ? 1 : 0;
    EXPECT_EQ(changed, 0u) << "knee " << knee;
  }
}

// The soft threshold's curve, on uniform frames (the blur keeps a uniform image uniform):
// out = b + intensity * max((b - t + k)^2 / 4k on the knee, b - t), 0 below t - k.
TEST_F(OracleBloom, SoftKneeFollowsItsQuadratic) {
  const double t = 1.0, k = 0.5;
  for (double v : {0.4, 0.6, 0.8, 1.0, 1.2, 1.5, 1.7, 3.0}) {
    Bloom b;
    b.mode = 1;
    b.threshold = t;
    b.knee = k;
    b.value = v;
    b.intensity = 1.0;
    const auto r = run(b);
    double bright = v - t;
    if (v > t - k && v < t + k) bright = std::max(bright, (v - t + k) * (v - t + k) / (4.0 * k));
    bright = std::max(bright, 0.0);
    const double want = v + b.intensity * bright;
    // The shader's knee denominator carries 1e-5 against a zero knee: 1e-5 / 4k relative.
    const double tol = kRel * want + bright * 1e-5 / (4.0 * k);
    for (int probe : {0, 32 * kSize + 32, kSize * kSize - 1})
      EXPECT_NEAR(r.at("out").v[static_cast<size_t>(probe)], want, tol) << "b = " << v << " at texel " << probe;
  }
}
