// Shadow maps against exact visibility (issue 28): a scene with a floor, a
// box resting on it, a pillar and a floating slab, lit by one light at a time
// (directional, spot, point), rendered by deferred-pbr-shadows.json with hard
// shadows and without shadows. Where the light reaches a pixel, the ratio of
// the two frames says whether the map shadows it; the CPU ray caster
// (tests/support/visibility_oracle.h) says whether it should. Away from
// shadow edges (every probe within 2 texels of the pixel's surface point
// classified alike, texels of the map that covers it) and from silhouettes,
// the two must agree on >= 99.5% of the probed pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rgraph/adapt.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/passes/shadow_views.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "shadow_scene.h"
#include "support/render_util.h"
#include "support/test_support.h"
#include "visibility_oracle.h"

namespace {
using namespace rgraph;
using nlohmann::json;
using oracle::Visibility;

constexpr Extent kSize{400, 300};

struct Agreement {
  int probes = 0, agree = 0, lit = 0, shadowed = 0, edges = 0;
  double share() const { return probes ? double(agree) / probes : 0.0; }
};

// The map texel covering `p` (for the edge margin): the cascade its view depth
// falls in, the spot map, or the point light's face its direction selects.
float texelAt(const std::vector<shadows::ShadowView>& views, const Camera& cam, const glm::vec3& p) {
  const shadows::ShadowView* pick = &views.front();
  if (views.front().kind == shadows::LightKind::directional) {
    const float depth = glm::dot(p - cam.position, glm::normalize(cam.target - cam.position));
    for (const auto& v : views)
      if (depth >= v.splitNear && depth < v.splitFar) pick = &v;
  } else if (views.front().kind == shadows::LightKind::point) {
    const glm::vec3 d = p - views.front().lightPosition, a = glm::abs(d);
    const int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0 ? 0 : 1) : a.y >= a.z ? (d.y >= 0 ? 2 : 3) : (d.z >= 0 ? 4 : 5);
    pick = &views[static_cast<size_t>(face)];
  }
  return shadows::texelFootprint(*pick, p, shadowtest::kMapSize);
}

template <class Light>
Agreement compare(const Scene& scene, const Light& light, const shadows::ShadowedLight& assigned) {
  ShaderLibrary shaders;
  const rtest::Image withShadows = shadowtest::render(scene, kSize, shaders, "hard");
  const rtest::Image without = shadowtest::render(scene, kSize, shaders, "");
  rtest::saveImage(withShadows, std::string("shadow-oracle-") + shadowtest::kindName(assigned.kind));
  const oracle::VisibilityOracle exact(scene);
  shadows::ShadowSettings settings;
  settings.resolution = shadowtest::kMapSize;
  const float aspect = float(kSize.width) / float(kSize.height);
  const auto views = shadows::shadowViews(scene, scene.camera, aspect, settings, {assigned});
  const Camera& cam = scene.camera;

  Agreement a;
  auto probeAt = [&](int x, int row) {
    return exact.probeAtPixel(cam, int(kSize.width), int(kSize.height), x + 0.5, kSize.height - row - 0.5);
  };
  for (int row = 2; row < int(kSize.height) - 2; row += 2)
    for (int x = 2; x < int(kSize.width) - 2; x += 2) {
      const glm::ivec3 un = without.rgb(x, row), sh = withShadows.rgb(x, row);
      const int unLum = std::max({un.r, un.g, un.b});
      if (unLum < 24) continue;  // the light adds too little here to tell
      const auto probe = probeAt(x, row);
      if (!probe) continue;
      // Silhouettes and creases: the neighbours must lie on the same plane.
      bool flat = true;
      for (auto [dx, dr] : {std::pair{2, 0}, {-2, 0}, {0, 2}, {0, -2}}) {
        const auto n = probeAt(x + dx, row + dr);
        if (!n || glm::dot(n->normal, probe->normal) < 0.999) flat = false;
      }
      if (!flat) continue;
      const Visibility v = exact.classify(*probe, light);
      if (v == Visibility::outside) continue;
      // Edges: any point within 2 texels (plus a half for the texel's own
      // extent) classified otherwise.
      const glm::dvec3 n = probe->normal;
      const glm::dvec3 t = glm::normalize(glm::cross(n, std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
      const glm::dvec3 b = glm::cross(n, t);
      const double r = 2.5 * texelAt(views, cam, glm::vec3(probe->point));
      bool edge = false;
      for (int k = 0; k < 16 && !edge; ++k) {
        const double ang = k * 3.14159265358979 / 8.0;
        oracle::VisibilityOracle::Probe q{probe->point + r * (std::cos(ang) * t + std::sin(ang) * b), n};
        const Visibility w = exact.classify(q, light);
        edge = (w == Visibility::shadowed) != (v == Visibility::shadowed);
      }
      if (edge) {
        ++a.edges;
        continue;
      }
      const bool mapShadowed = std::max({sh.r, sh.g, sh.b}) < unLum / 2;
      ++a.probes;
      a.agree += mapShadowed == (v == Visibility::shadowed);
      (v == Visibility::shadowed ? a.shadowed : a.lit) += 1;
    }
  std::printf("[ measure  ] %s: %d probes (%d lit, %d shadowed, %d near edges left out), %.3f%% agree\n",
              shadowtest::kindName(assigned.kind), a.probes, a.lit, a.shadowed, a.edges, 100.0 * a.share());
  return a;
}

class ShadowOracle : public rtest::RenderTest {};

TEST_F(ShadowOracle, HardDirectionalCascadesAgreeWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.directionalLights.push_back(shadowtest::sun());
  const Agreement a = compare(scene, scene.directionalLights[0], {shadows::LightKind::directional, 0, 0, 4});
  EXPECT_GE(a.lit, 1000);
  EXPECT_GE(a.shadowed, 300);
  EXPECT_GE(a.share(), 0.995);
}

TEST_F(ShadowOracle, HardSpotMapAgreesWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.pointLights.push_back(shadowtest::spot());
  const Agreement a = compare(scene, scene.pointLights[0], {shadows::LightKind::spot, 0, 0, 1});
  EXPECT_GE(a.lit, 1000);
  EXPECT_GE(a.shadowed, 300);
  EXPECT_GE(a.share(), 0.995);
}

TEST_F(ShadowOracle, HardPointCubeAgreesWithExactVisibilityAwayFromEdges) {
  Scene scene = shadowtest::testScene();
  scene.pointLights.push_back(shadowtest::point());
  const Agreement a = compare(scene, scene.pointLights[0], {shadows::LightKind::point, 0, 0, 6});
  EXPECT_GE(a.lit, 1000);
  EXPECT_GE(a.shadowed, 300);
  EXPECT_GE(a.share(), 0.995);
}

}  // namespace
