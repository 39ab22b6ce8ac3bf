// The visibility oracle on scenes whose shadows are known in closed form: a
// unit box over a floor under a directional, a point and a spot light; the
// self-intersection rule (grazing light on a flat floor, a point just under a
// caster); casters that do not cast; spin; the batch form.
#include <gtest/gtest.h>

#include <random>

#include "visibility_test_util.h"

namespace {

using namespace rgraph;
using namespace rgraph::oracle;
using namespace vistest;

const dvec3 kBoxLo(-0.5, 1.5, -0.5), kBoxHi(0.5, 2.5, 0.5);  // boxOverFloor()'s box

// The box's shadow on the floor y = 0: the convex hull of its 8 corners
// projected along the light's rays (`project` maps a corner to the floor).
template <typename Project>
std::vector<dvec2> shadowPolygon(Project project) {
  std::vector<dvec2> pts;
  for (int i = 0; i < 8; ++i) {
    const dvec3 v(i & 1 ? kBoxHi.x : kBoxLo.x, i & 2 ? kBoxHi.y : kBoxLo.y, i & 4 ? kBoxHi.z : kBoxLo.z);
    const dvec3 s = project(v);
    pts.push_back({s.x, s.z});
  }
  return convexHull(pts);
}

// For each edge of the shadow polygon, points a margin outside must be lit
// and a margin inside shadowed (at 5 places along the edge, not at corners).
template <typename Classify>
void expectEdgesFollowPolygon(const std::vector<dvec2>& hull, double margin, Classify classify) {
  ASSERT_GE(hull.size(), 4u);
  for (size_t i = 0; i < hull.size(); ++i) {
    const dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    const dvec2 along = b - a;
    const dvec2 outward = glm::normalize(dvec2(along.y, -along.x));
    for (double f : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const dvec2 m = a + along * f;
      const dvec2 out = m + outward * margin, in = m - outward * margin;
      EXPECT_EQ(classify(dvec3(out.x, 0.0, out.y)), Visibility::lit) << "edge " << i << " at " << f << " outside";
      EXPECT_EQ(classify(dvec3(in.x, 0.0, in.y)), Visibility::shadowed) << "edge " << i << " at " << f << " inside";
    }
  }
}

TEST(VisibilityOracle, DirectionalStraightDownShadowIsTheBoxFootprint) {
  const VisibilityOracle oracle(boxOverFloor());
  DirectionalLight sun;
  sun.direction = {0.0f, -1.0f, 0.0f};
  const auto hull = shadowPolygon([](const dvec3& v) { return dvec3(v.x, 0.0, v.z); });
  expectEdgesFollowPolygon(hull, 1e-6, [&](const dvec3& p) { return oracle.classify(p, sun); });
  // And the footprint itself, on a grid: inside |x|, |z| < 0.5 shadowed, outside lit.
  int shadowed = 0;
  for (double x = -1.0; x <= 1.0; x += 0.0625)
    for (double z = -1.0; z <= 1.0; z += 0.0625) {
      const double edge = std::min(std::abs(std::abs(x) - 0.5), std::abs(std::abs(z) - 0.5));
      if (edge < 1e-9) continue;
      const bool inside = std::abs(x) < 0.5 && std::abs(z) < 0.5;
      EXPECT_EQ(oracle.visible(dvec3(x, 0.0, z), sun), !inside) << x << ", " << z;
      shadowed += inside;
    }
  EXPECT_EQ(shadowed, 15 * 15);
}

TEST(VisibilityOracle, TiltedDirectionalShadowIsTheProjectedBox) {
  const VisibilityOracle oracle(boxOverFloor());
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(0.7f, -1.0f, 0.3f));
  const dvec3 d(sun.direction);
  const auto hull = shadowPolygon([&](const dvec3& v) { return v - d * (v.y / d.y); });
  expectEdgesFollowPolygon(hull, 1e-6, [&](const dvec3& p) { return oracle.classify(p, sun); });
}

TEST(VisibilityOracle, PointLightShadowEdgesAreTheProjectionFromTheLight) {
  const VisibilityOracle oracle(boxOverFloor());
  PointLight light;
  light.position = {0.75f, 6.0f, -0.5f};
  const dvec3 l(light.position);
  // Corner v seen from l lands on the floor at l + (v - l) * l.y / (l.y - v.y).
  const auto hull = shadowPolygon([&](const dvec3& v) { return l + (v - l) * (l.y / (l.y - v.y)); });
  expectEdgesFollowPolygon(hull, 1e-6, [&](const dvec3& p) { return oracle.classify(p, light); });
  // Random floor points against the analytic segment-box test, away from edges.
  std::mt19937 rng(28);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  int checked = 0, inShadow = 0;
  for (int i = 0; i < 4000; ++i) {
    const dvec3 p(u(rng), 0.0, u(rng));
    const double overlap = segmentBoxOverlap(p, l - p, 0.0, 1.0, kBoxLo, kBoxHi);
    if (std::abs(overlap) < 1e-6) continue;  // grazing an edge of the box
    ++checked;
    inShadow += overlap > 0.0;
    EXPECT_EQ(oracle.classify(p, light), overlap > 0.0 ? Visibility::shadowed : Visibility::lit) << p.x << ", " << p.z;
  }
  EXPECT_GT(checked, 3900);
  EXPECT_GT(inShadow, 100);
}

TEST(VisibilityOracle, SpotLightOutsideItsConeIsOutside) {
  const VisibilityOracle oracle(boxOverFloor());
  PointLight spot;
  spot.spot = true;
  spot.position = {0.0f, 5.0f, 0.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.outerConeDeg = 30.0f;
  spot.innerConeDeg = 20.0f;
  const double coneRadius = 5.0 * std::tan(30.0 * 3.14159265358979323846 / 180.0);  // on the floor
  for (double angle = 0.0; angle < 6.28; angle += 0.5) {
    const dvec3 dir(std::cos(angle), 0.0, std::sin(angle));
    EXPECT_EQ(oracle.classify(dir * (coneRadius - 1e-6), spot), Visibility::lit) << angle;
    EXPECT_EQ(oracle.classify(dir * (coneRadius + 1e-6), spot), Visibility::outside) << angle;
    EXPECT_FALSE(oracle.visible(dir * (coneRadius + 1e-6), spot));
  }
  EXPECT_EQ(oracle.classify(dvec3(0.1, 0.0, 0.2), spot), Visibility::shadowed);  // under the box, in the cone
  // Outside the cone wins over the caster: a point the box hides but the cone misses.
  spot.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  EXPECT_EQ(oracle.classify(dvec3(0.0, 0.0, 0.0), spot), Visibility::outside);
  // The cone is the outer angle exactly: 44.9 degrees off a 45-degree cone is in.
  spot.outerConeDeg = 45.0f;
  spot.direction = {0.0f, -1.0f, 0.0f};
  const double r449 = 5.0 * std::tan(44.9 * 3.14159265358979323846 / 180.0);
  EXPECT_EQ(oracle.classify(dvec3(r449, 0.0, 0.0), spot), Visibility::lit);
}

TEST(VisibilityOracle, NonCastersAreIgnored) {
  Scene s = boxOverFloor();
  DirectionalLight sun;
  EXPECT_FALSE(VisibilityOracle(s).visible(dvec3(0.0), sun));
  s.primitives[0].castShadows = false;
  const VisibilityOracle oracle(s);
  EXPECT_TRUE(oracle.visible(dvec3(0.0), sun));
  EXPECT_EQ(oracle.bvh().stats().triangles, 2u);  // the floor only
  for (const WorldTriangle& t : oracle.bvh().triangles()) EXPECT_EQ(t.primitive, 1);
  // A light below the floor: the floor casts on the box's bottom face.
  PointLight below;
  below.position = {0.0f, -1.0f, 0.0f};
  EXPECT_FALSE(oracle.visible(dvec3(0.0, 1.5, 0.0), below));
  s.primitives[1].castShadows = false;
  EXPECT_TRUE(VisibilityOracle(s).visible(dvec3(0.0, 1.5, 0.0), below));
}

// A blended box (glass) lets the light through unless it says it casts.
TEST(VisibilityOracle, BlendedPrimitivesCastOnlyWhenTheySaySo) {
  Scene s = boxOverFloor();
  Material glass;
  glass.alphaMode = AlphaMode::blend;
  s.materials.push_back(glass);
  s.primitives[0].material = int(s.materials.size()) - 1;
  DirectionalLight sun;
  EXPECT_TRUE(VisibilityOracle(s).visible(dvec3(0.0), sun));
  s.primitives[0].castShadows = true;
  EXPECT_FALSE(VisibilityOracle(s).visible(dvec3(0.0), sun));
}

TEST(VisibilityOracle, EpsilonIsRelativeToTheCastersBox) {
  const VisibilityOracle oracle(boxOverFloor());
  const double diagonal = std::sqrt(100.0 * 100.0 * 2.0 + 2.5 * 2.5);  // floor 100 x 100, box top at 2.5
  EXPECT_NEAR(oracle.epsilon(), VisibilityOracle::kRelativeEpsilon * diagonal, 1e-12);
  EXPECT_EQ(VisibilityOracle(boxOverFloor({0.0f, 2.0f, 0.0f}, 50.0f, glm::vec3(1e5f))).epsilon(), oracle.epsilon());
}

// The self-intersection rule: a flat lit floor stays lit down to 1 degree of
// elevation, for float-rounded positions (what a G-buffer holds), with and
// without the normal. The floor is tilted (17 degrees about (1, 0, 1)) so
// that rounding moves the points off its plane (a level floor's y = 0 is exact in float).
TEST(VisibilityOracle, FlatFloorIsLitAtGrazingAngles) {
  Scene s = boxOverFloor({0.0f, 2.0f, 0.0f}, 50.0f);
  s.primitives[0].castShadows = false;  // the floor alone
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(17.0f), glm::normalize(glm::vec3(1, 0, 1)));
  s.primitives[1].transform = tilt;
  const glm::dmat4 m(tilt);
  auto onFloor = [&](const dvec3& local) { return dvec3(m * glm::dvec4(local, 1.0)); };
  const dvec3 up = glm::normalize(dvec3(m * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
  const VisibilityOracle oracle(s);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-45.0, 45.0);
  int offPlane = 0;
  for (double elevation : {1.0, 2.0, 5.0, 15.0, 45.0, 89.0}) {
    for (double azimuth : {0.0, 1.3, 2.9, 4.4}) {
      const double e = elevation * 3.14159265358979323846 / 180.0;
      const dvec3 toLight = onFloor(dvec3(std::cos(e) * std::cos(azimuth), std::sin(e), std::cos(e) * std::sin(azimuth))) -
                            onFloor(dvec3(0.0));
      DirectionalLight sun;
      sun.direction = -glm::vec3(toLight);
      PointLight lamp;  // 40 units away at the same elevation
      for (int i = 0; i < 200; ++i) {
        const dvec3 exact = onFloor(dvec3(u(rng), 0.0, u(rng)));
        const dvec3 p = floatRounded(exact);
        offPlane += glm::dot(p - onFloor(dvec3(0.0)), up) != 0.0;
        lamp.position = glm::vec3(p + toLight * 40.0);
        ASSERT_TRUE(oracle.visible(p, sun)) << "elevation " << elevation << " at " << p.x << ", " << p.z;
        ASSERT_TRUE(oracle.visible(p, lamp)) << "elevation " << elevation;
        ASSERT_EQ(oracle.classify({p, up}, sun), Visibility::lit);
        ASSERT_EQ(oracle.classify({p, up}, lamp), Visibility::lit);
      }
    }
  }
  EXPECT_GT(offPlane, 4000);  // rounding did move the points off the plane
  // A light under the floor: the floor itself shadows its points (with the
  // normal the ray starts above the floor and must cross it).
  DirectionalLight fromBelow;
  fromBelow.direction = glm::vec3(up);
  EXPECT_EQ(oracle.classify({floatRounded(onFloor(dvec3(1.0 / 3.0, 0.0, 0.1))), up}, fromBelow), Visibility::shadowed);
}

TEST(VisibilityOracle, PointJustUnderACasterIsShadowed) {
  // The box's bottom 0.01 above the floor (7 epsilons), then resting on it.
  for (float gap : {0.01f, 0.0f}) {
    const VisibilityOracle oracle(boxOverFloor({0.0f, 0.5f + gap, 0.0f}));
    DirectionalLight sun;
    PointLight lamp;
    lamp.position = {0.25f, 4.0f, 0.0f};
    for (double x = -0.45; x <= 0.45; x += 0.05) {
      const dvec3 p = floatRounded(dvec3(x, 0.0, 0.2));
      EXPECT_FALSE(oracle.visible(p, sun)) << "gap " << gap << " x " << x;
      EXPECT_FALSE(oracle.visible(p, lamp)) << "gap " << gap << " x " << x;
      EXPECT_EQ(oracle.classify({p, dvec3(0.0, 1.0, 0.0)}, sun), Visibility::shadowed);
    }
    // Just outside the footprint, sun straight down: lit.
    EXPECT_TRUE(oracle.visible(dvec3(0.5 + 1e-6, 0.0, 0.2), sun)) << gap;
  }
  // The box's own faces: a point on its top face is lit from above, on its
  // bottom face shadowed (the box itself is in the way).
  const VisibilityOracle oracle(boxOverFloor());
  DirectionalLight sun;
  EXPECT_TRUE(oracle.visible(floatRounded(dvec3(0.1, 2.5, 0.1)), sun));
  EXPECT_FALSE(oracle.visible(floatRounded(dvec3(0.1, 1.5, 0.1)), sun));
}

TEST(VisibilityOracle, LightInsideACasterSeesNothingOutside) {
  const VisibilityOracle oracle(boxOverFloor());
  PointLight inside;
  inside.position = {0.0f, 2.0f, 0.0f};
  EXPECT_FALSE(oracle.visible(dvec3(3.0, 0.0, 1.0), inside));
  EXPECT_FALSE(oracle.visible(dvec3(0.0, 5.0, 0.0), inside));
  EXPECT_TRUE(oracle.visible(dvec3(0.2, 2.1, -0.1), inside));  // inside the box with it
}

TEST(VisibilityOracle, LightOnASurfaceIsNotBlockedByIt) {
  const VisibilityOracle oracle(boxOverFloor());
  PointLight onTop;
  onTop.position = {0.1f, 2.5f, 0.3f};  // on the box's top face (float: up to rounding)
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 1000; ++i) {
    const dvec3 p(u(rng), 2.5 + std::abs(u(rng)) + 0.01, u(rng));  // above the top face's plane
    ASSERT_TRUE(oracle.visible(p, onTop)) << i;
  }
  EXPECT_FALSE(oracle.visible(dvec3(3.0, 0.0, 0.0), onTop));  // the segment dives into the box, out of its side
}

TEST(VisibilityOracle, SpinIsIgnoredTheStaticTransformCounts) {
  Scene s = boxOverFloor();
  const auto still = shadowCasterTriangles(s);
  s.primitives[0].spin.degreesPerSecond = 90.0f;
  s.primitives[0].spin.pivot = {0.0f, 2.0f, 0.0f};
  s.primitives[0].spin.axis = {0.0f, 0.0f, 1.0f};
  const auto spinning = shadowCasterTriangles(s);
  ASSERT_EQ(still.size(), spinning.size());
  for (size_t i = 0; i < still.size(); ++i) EXPECT_EQ(still[i].a, spinning[i].a);
}

TEST(VisibilityOracle, BatchAnswersAreTheSingleAnswers) {
  const VisibilityOracle oracle(boxOverFloor());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<VisibilityOracle::Probe> probes;
  for (int i = 0; i < 5000; ++i) probes.push_back({dvec3(u(rng), 0.0, u(rng)), i % 2 ? dvec3(0, 1, 0) : dvec3(0.0)});
  PointLight spot;
  spot.spot = true;
  spot.position = {0.5f, 4.0f, 0.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.outerConeDeg = 20.0f;
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.4f));
  for (int threads : {1, 3, 0}) {
    const auto spotAnswers = oracle.classify(probes, spot, threads);
    const auto sunAnswers = oracle.classify(probes, sun, threads);
    ASSERT_EQ(spotAnswers.size(), probes.size());
    int kinds[3] = {0, 0, 0};
    for (size_t i = 0; i < probes.size(); ++i) {
      ASSERT_EQ(spotAnswers[i], oracle.classify(probes[i], spot)) << i;
      ASSERT_EQ(sunAnswers[i], oracle.classify(probes[i], sun)) << i;
      ++kinds[static_cast<int>(spotAnswers[i])];
    }
    EXPECT_GT(kinds[0], 100);  // every answer occurs
    EXPECT_GT(kinds[1], 100);
    EXPECT_GT(kinds[2], 100);
  }
}

// Probes placed by the camera land where the camera's float view-projection
// puts them: projected back, each falls on its own pixel centre.
TEST(VisibilityOracle, PixelProbesAreWhereTheCameraSees) {
  const VisibilityOracle oracle(boxOverFloor());
  Camera cam;
  cam.position = {1.0f, 6.0f, 7.0f};
  cam.target = {0.0f, 1.0f, 0.0f};
  cam.fovY = 50.0f;
  const int w = 64, h = 48;
  const glm::dmat4 vp(cam.viewProjection(float(w) / float(h)));
  int onBox = 0, onFloor = 0, sky = 0, shadowed = 0;
  DirectionalLight sun;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const auto probe = oracle.probeAtPixel(cam, w, h, px + 0.5, py + 0.5);
      if (!probe) {
        ++sky;
        continue;
      }
      const glm::dvec4 clip = vp * glm::dvec4(probe->point, 1.0);
      EXPECT_NEAR((clip.x / clip.w + 1.0) * 0.5 * w, px + 0.5, 1e-3);
      EXPECT_NEAR((clip.y / clip.w + 1.0) * 0.5 * h, py + 0.5, 1e-3);
      EXPECT_LT(glm::dot(probe->normal, probe->point - dvec3(cam.position)), 0.0);  // faces the camera
      const bool box = probe->point.y > 1e-9;
      onBox += box;
      onFloor += !box;
      shadowed += oracle.classify(*probe, sun) == Visibility::shadowed;
    }
  EXPECT_GT(onBox, 50);
  EXPECT_GT(onFloor, 500);
  EXPECT_EQ(sky, 0);  // the floor fills the view
  EXPECT_GT(shadowed, 20);  // the footprint under the box shows
  // Looking up: nothing.
  cam.target = {0.0f, 20.0f, 0.0f};
  EXPECT_FALSE(oracle.probeAtPixel(cam, w, h, 32.5, 24.5));
  // Beyond the far plane: nothing either.
  cam.target = {0.0f, 1.0f, 0.0f};
  cam.far = 2.0f;
  EXPECT_FALSE(oracle.probeAtPixel(cam, w, h, 32.5, 24.5));
}

TEST(VisibilityOracle, NamesTheAnswers) {
  EXPECT_STREQ(visibilityName(Visibility::lit), "lit");
  EXPECT_STREQ(visibilityName(Visibility::shadowed), "shadowed");
  EXPECT_STREQ(visibilityName(Visibility::outside), "outside");
}

TEST(VisibilityOracle, MeshIndexOutOfRangeIsAnError) {
  Scene s = boxOverFloor();
  s.primitives[1].mesh = 7;
  try {
    shadowCasterTriangles(s);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("primitive 1 ('floor'): mesh 7 out of range (2 meshes)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
