// The tonemap pass against the oracle of lighting_oracle.h (exposure, the
// none / Reinhard / ACES-fit curves, clamp, then the exact sRGB curve or
// pow(1/gamma), as the pass's parameters document them), on every pixel of a
// frame: the rgba32f HDR input is read back and the oracle applied to it in
// double precision, then compared with the rgba8 output.
//
// Tolerance, per channel: 0.5/255 (the output is rounded to 8 bits) plus
// 1e-4 of full scale for the fp32 evaluation of the curves (pow, division;
// a few ulps each, far below 1e-4). Measured worst errors are printed.
#include <cstdio>
#include <string>
#include <vector>

#include "oracle/lighting_oracle.h"
#include "support/render_util.h"
#include "render/test_scenes.h"

using namespace rgraph;
using namespace rgraph::rtest;
namespace o = rgraph::oracle;

namespace {

constexpr Extent kSize{64, 64};
constexpr double kToleranceBytes = 0.5 + 255.0 * 1e-4;

// A lit plane whose HDR values run from 0 (background, top rows) through the whole
// curve to well above 1 (under the bright light).
Scene brightPlane() {
  Scene s;
  s.source = "test:oracle-tonemap";
  const int plane = addMesh(s, makePlane(3.0f, 3.0f));
  addDraw(s, plane, addMaterial(s, {0.8f, 0.6f, 0.4f, 1.0f}, 0.0f, 0.5f, 0.6f), glm::mat4(1.0f), "plane");
  s.pointLights.push_back(pointLight({0.0f, 0.5f, 0.0f}, {6.0f, 4.0f, 2.0f}, 1.0f, 0.35f, 0.44f));
  s.pointLights.push_back(pointLight({-2.0f, 0.8f, -1.0f}, {0.5f, 1.0f, 3.0f}, 1.0f, 0.35f, 0.44f));
  s.ambient = glm::vec3(0.002f);
  s.camera.position = glm::vec3(0.0f, 4.0f, 3.0f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.far = 30.0f;
  s.hasCamera = true;
  return s;
}

struct Case {
  const char* op;
  o::Curve curve;
  double exposure, gamma;
  bool dim = false;  // exposure so low that most values fall on the sRGB curve's linear segment
};

class OracleToneMap : public RenderTest {
 protected:
  void check(const Case& c) {
    SCOPED_TRACE(std::string("operator ") + c.op + ", exposure " + std::to_string(c.exposure) + ", gamma " +
                 std::to_string(c.gamma));
    PipelineConfig cfg = loadPipeline(testPipeline("deferred-fp32.json"));
    setParam(cfg, "tonemap", "operator", std::string(c.op));
    setParam(cfg, "tonemap", "exposure", c.exposure);
    setParam(cfg, "tonemap", "gamma", c.gamma);
    std::vector<float> hdr;
    const Image out = render(cfg, brightPlane(), kSize, *shaders,
                             [&](Executor& e) { hdr = e.readTextureRGBA32F("hdr_forward"); });
    ASSERT_EQ(hdr.size(), out.rgba.size());
    // The frame must exercise the curve: dark, mid and clipped values.
    size_t dark = 0, mid = 0, over = 0, linear = 0;
    double worst = 0.0;
    for (size_t i = 0; i < hdr.size(); i += 4)
      for (size_t ch = 0; ch < 3; ++ch) {
        const double v = hdr[i + ch] * c.exposure;
        dark += v < 0.1;
        mid += v > 0.1 && v < 0.9;
        over += v > 1.5;
        linear += v > 0.001 && v <= 0.0031308;
        const double want = 255.0 * o::toneMap(hdr[i + ch], c.curve, c.exposure, c.gamma);
        const double err = std::abs(out.rgba[i + ch] - want);
        worst = std::max(worst, err);
        const size_t px = i / 4;
        EXPECT_LE(err, kToleranceBytes) << "pixel (" << px % kSize.width << "," << px / kSize.width << ") channel "
                                        << ch << ": hdr " << hdr[i + ch] << ", output " << int(out.rgba[i + ch])
                                        << ", oracle " << want;
      }
    if (c.dim) {
      EXPECT_GT(linear, 1000u);
    } else {
      EXPECT_GT(dark, 50u);
      EXPECT_GT(mid, 1000u);
      EXPECT_GT(over, 30u);
    }
    std::printf("[ measure  ] tonemap %s exposure %g gamma %g: worst error %.3f/255 (tolerance %.3f)\n", c.op,
                c.exposure, c.gamma, worst, kToleranceBytes);
  }
};

}  // namespace

TEST_F(OracleToneMap, NoCurveExactSrgb) { check({"none", o::Curve::none, 1.0, 0.0}); }
TEST_F(OracleToneMap, NoCurveSrgbLinearSegment) { check({"none", o::Curve::none, 0.004, 0.0, true}); }
TEST_F(OracleToneMap, NoCurveExposureAndGamma) { check({"none", o::Curve::none, 2.5, 2.2}); }
TEST_F(OracleToneMap, Reinhard) { check({"reinhard", o::Curve::reinhard, 1.5, 0.0}); }
TEST_F(OracleToneMap, ReinhardGamma) { check({"reinhard", o::Curve::reinhard, 4.0, 1.8}); }
TEST_F(OracleToneMap, AcesFit) { check({"aces", o::Curve::aces, 0.8, 0.0}); }
TEST_F(OracleToneMap, AcesFitExposureAndGamma) { check({"aces", o::Curve::aces, 3.0, 2.4}); }
