// Shadow maps against exact visibility (issue 28): a scene with a floor, a
// box resting on it, a pillar and a floating slab, lit by one light at a time
// (directional, spot, point), rendered by deferred-pbr-shadows.json with hard
// shadows and without shadows. Where the light reaches a pixel, the ratio of
// the two frames says whether the map shadows it; the CPU ray caster
// (tests/support/visibility_oracle.h) says whether it should. Away from
// shadow edges (every point within 2 texels of the pixel's surface point
// classified alike, in texels of the map that covers it) and from
// silhouettes, the two must agree on >= 99.5% of the probed pixels.
#include <gtest/gtest.h>

#include "shadow_probe.h"

namespace {
using namespace rgraph;
using shadowtest::agreement;
using shadows::LightKind;

class ShadowOracle : public rtest::RenderTest {};

void expectAgreement(const shadowtest::Agreement& a) {
  EXPECT_GE(a.lit, 1000);
  EXPECT_GE(a.shadowed, 300);  // enough of both that neither answer alone passes
  EXPECT_GE(a.share(), 0.995);
}

TEST_F(ShadowOracle, HardDirectionalCascadesAgreeWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.directionalLights.push_back(shadowtest::sun());
  expectAgreement(agreement(scene, scene.directionalLights[0], {LightKind::directional, 0, 0, 4}, {}, "oracle-directional"));
}

TEST_F(ShadowOracle, HardSpotMapAgreesWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.pointLights.push_back(shadowtest::spot());
  expectAgreement(agreement(scene, scene.pointLights[0], {LightKind::spot, 0, 0, 1}, {}, "oracle-spot"));
}

TEST_F(ShadowOracle, HardPointCubeAgreesWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.pointLights.push_back(shadowtest::point());
  expectAgreement(agreement(scene, scene.pointLights[0], {LightKind::point, 0, 0, 6}, {}, "oracle-point"));
}

// The filters soften edges but must not move them: away from edges PCF and
// PCSS agree with exact visibility as hard shadows do.
TEST_F(ShadowOracle, PcfAndPcssAgreeAwayFromEdgesToo) {
  Scene scene = shadowtest::testScene();
  scene.directionalLights.push_back(shadowtest::sun());
  for (const char* filter : {"pcf", "pcss"}) {
    shadowtest::ProbeOptions o;
    o.filter = filter;
    o.edgeTexels = 5.5;  // the kernel's reach: 3x3 bilinear taps and pcss's widened kernel
    expectAgreement(agreement(scene, scene.directionalLights[0], {LightKind::directional, 0, 0, 4}, o,
                              std::string("oracle-directional-") + filter));
  }
}

}  // namespace
