// The oracle far from the origin, at huge and tiny scales, on degenerate and
// empty inputs, and on real glTF models.
#include <gtest/gtest.h>

#include <random>

#include "visibility_test_util.h"

namespace {

using namespace rgraph;
using namespace rgraph::oracle;
using namespace vistest;

const dvec3 kBoxLo(-0.5, 1.5, -0.5), kBoxHi(0.5, 2.5, 0.5);  // boxOverFloor()'s box

struct Lights {
  DirectionalLight sun;
  PointLight point, spot;
};

// Positions on a 1/8 grid: exact in float at 1e5 (whose float spacing is 1/128).
Lights testLights(double offset, double scale) {
  Lights l;
  l.sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.25f));
  l.point.position = glm::vec3(dvec3(0.625, 5.0, -0.375) * scale + dvec3(offset));
  l.spot = l.point;
  l.spot.spot = true;
  l.spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.1f));
  l.spot.outerConeDeg = 25.0f;
  return l;
}

// Floor points in the unit scene where every light's answer is decided by a
// margin: the shadow ray does not graze the box.
std::vector<dvec3> decidedFloorPoints(const Lights& l) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<dvec3> out;
  while (out.size() < 2000) {
    const dvec3 p(std::round(u(rng) * 1024.0) / 1024.0, 0.0, std::round(u(rng) * 1024.0) / 1024.0);
    const double sunOverlap = segmentBoxOverlap(p, -dvec3(l.sun.direction), 0.0, 1e30, kBoxLo, kBoxHi);
    const double pointOverlap = segmentBoxOverlap(p, dvec3(l.point.position) - p, 0.0, 1.0, kBoxLo, kBoxHi);
    const dvec3 fromSpot = glm::normalize(p - dvec3(l.spot.position));
    const double cone = glm::dot(fromSpot, dvec3(l.spot.direction)) - std::cos(25.0 * 3.14159265358979323846 / 180.0);
    if (std::abs(sunOverlap) > 1e-4 && std::abs(pointOverlap) > 1e-4 && std::abs(cone) > 1e-4) out.push_back(p);
  }
  return out;
}

// The box scene offset and scaled gives the unit scene's answers at the same
// (offset and scaled) points, with and without normals.
void expectSameAnswers(double offset, double scale) {
  const Lights unit = testLights(0.0, 1.0), moved = testLights(offset, scale);
  Scene s = boxOverFloor({0.0f, 2.0f * float(scale), 0.0f}, 50.0f * float(scale), glm::vec3(float(offset)));
  s.primitives[0].transform = glm::scale(s.primitives[0].transform, glm::vec3(float(scale)));
  const VisibilityOracle reference(boxOverFloor()), oracle(s);
  int shadowed = 0;
  for (const dvec3& p : decidedFloorPoints(unit)) {
    const dvec3 q = p * scale + dvec3(offset);
    for (const dvec3& n : {dvec3(0.0), dvec3(0.0, 1.0, 0.0)}) {
      const Visibility sun = reference.classify({p, n}, unit.sun);
      ASSERT_EQ(oracle.classify({q, n}, moved.sun), sun) << p.x << ", " << p.z;
      ASSERT_EQ(oracle.classify({q, n}, moved.point), reference.classify({p, n}, unit.point)) << p.x << ", " << p.z;
      ASSERT_EQ(oracle.classify({q, n}, moved.spot), reference.classify({p, n}, unit.spot)) << p.x << ", " << p.z;
      shadowed += sun == Visibility::shadowed;
    }
  }
  EXPECT_GT(shadowed, 50);
}

TEST(VisibilityOracleRobustness, SameAnswersFarFromTheOrigin) { expectSameAnswers(1e5, 1.0); }
TEST(VisibilityOracleRobustness, SameAnswersInHugeAndTinyScenes) {
  expectSameAnswers(0.0, 1e12);
  expectSameAnswers(0.0, 1e-9);
  expectSameAnswers(1e5, 1e3);
}

TEST(VisibilityOracleRobustness, DegenerateTrianglesDoNotBlockCrashOrHang) {
  std::vector<WorldTriangle> tris;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 500; ++i) {
    const dvec3 a(i * 0.01, 0.0, 0.0);
    tris.push_back({a, a, a, i});                                           // a point
    tris.push_back({a, a + dvec3(0.0, 0.0, 1.0), a + dvec3(0.0, 0.0, 2.0), i});  // collinear
  }
  tris.push_back({dvec3(nan), dvec3(0.0), dvec3(1.0), -1});
  tris.push_back({dvec3(0.0), dvec3(inf, 0.0, 0.0), dvec3(1.0), -1});
  tris.push_back({dvec3(0.0, 0.0, 0.5), dvec3(1.0, 0.0, 0.5), dvec3(0.0, 0.0, 0.6), 7});  // one real one
  const Bvh degenerate(tris);
  EXPECT_EQ(degenerate.stats().droppedNonFinite, 2u);
  EXPECT_EQ(degenerate.stats().droppedDegenerate, 1000u);
  EXPECT_EQ(degenerate.stats().triangles, 1u);
  // A ray down through the points and lines: they have no inside.
  Ray down;
  down.origin = dvec3(0.05, 1.0, 0.0);
  down.direction = dvec3(0.0, -1.0, 0.0);
  EXPECT_FALSE(degenerate.anyHit(down));
  EXPECT_FALSE(bruteForceAnyHit(tris, down));
  down.origin.z = 0.55;  // the real one is there
  EXPECT_TRUE(degenerate.anyHit(down));
  EXPECT_TRUE(bruteForceAnyHit(tris, down));
  down.origin.z = 0.0;
  // 3000 copies of one triangle (all centroids equal: no SAH split exists).
  std::vector<WorldTriangle> copies(3000, WorldTriangle{dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 0, 1), 0});
  const Bvh same(copies);
  EXPECT_LE(same.stats().maxDepth, Bvh::kMaxDepth);
  EXPECT_LE(same.stats().maxLeafSize, size_t(4 * Bvh::kMaxLeafTriangles));
  down.origin = dvec3(0.2, 1.0, 0.2);
  EXPECT_TRUE(same.anyHit(down));
  ASSERT_TRUE(same.closestHit(down));
  EXPECT_DOUBLE_EQ(same.closestHit(down)->t, 1.0);
  // A ray with a NaN direction answers something and returns.
  down.direction = dvec3(nan);
  (void)same.anyHit(down);
  (void)same.closestHit(down);
}

TEST(VisibilityOracleRobustness, EmptySceneShadowsNothing) {
  const VisibilityOracle none{Scene{}};
  EXPECT_TRUE(none.visible(dvec3(1.0), DirectionalLight{}));
  EXPECT_TRUE(none.visible(dvec3(1.0), PointLight{}));
  EXPECT_FALSE(none.closestHit(dvec3(0.0), dvec3(1.0, 0.0, 0.0)));
  EXPECT_GT(none.epsilon(), 0.0);
  Scene onlyNonCasters = boxOverFloor();
  for (Primitive& p : onlyNonCasters.primitives) p.castShadows = false;
  EXPECT_EQ(VisibilityOracle(onlyNonCasters).bvh().stats().triangles, 0u);
}

// Probes placed by camera rays on the model (no G-buffer needed), then shadow
// rays from them: the BVH answers what brute force answers.
void checkModel(const std::string& file, size_t minTriangles) {
  const Scene scene = loadGltf(asset(file));
  const VisibilityOracle oracle(scene);
  const auto all = shadowCasterTriangles(scene);
  ASSERT_GE(all.size(), minTriangles);
  EXPECT_EQ(oracle.bvh().stats().triangles, all.size());
  EXPECT_LT(oracle.bvh().stats().sahCost, double(all.size()) / 100.0) << oracle.bvh().stats().sahCost;
  const dvec3 lo = oracle.bvh().boundsMin(), hi = oracle.bvh().boundsMax(), centre = (lo + hi) * 0.5;
  const double radius = glm::length(hi - lo);
  std::mt19937 rng(9);
  std::normal_distribution<double> n(0.0, 1.0);
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
  int onModel = 0, lit = 0, shadowed = 0;
  for (int i = 0; i < 300; ++i) {
    const dvec3 eye = centre + glm::normalize(dvec3(n(rng), n(rng), n(rng))) * radius;
    const dvec3 dir = centre + dvec3(n(rng), n(rng), n(rng)) * radius * 0.1 - eye;
    const auto hit = oracle.closestHit(eye, dir);
    Ray ray{eye, glm::normalize(dir), oracle.epsilon(), std::numeric_limits<double>::infinity()};
    const auto brute = bruteForceClosestHit(oracle.bvh().triangles(), ray);
    ASSERT_EQ(hit.has_value(), brute.has_value());
    if (!hit) continue;
    ASSERT_EQ(hit->t, brute->t);
    ++onModel;
    const dvec3 p = ray.origin + ray.direction * hit->t, normal = oracle.faceNormal(*hit, ray.direction);
    const Visibility v = oracle.classify({p, normal}, sun);
    Ray shadow{p + normal * oracle.epsilon(), -dvec3(sun.direction), 0.0, std::numeric_limits<double>::infinity()};
    EXPECT_EQ(v == Visibility::shadowed, bruteForceAnyHit(all, shadow));
    lit += v == Visibility::lit;
    shadowed += v == Visibility::shadowed;
  }
  EXPECT_GT(onModel, 100);
  EXPECT_GT(lit, 10);
  EXPECT_GT(shadowed, 10);
}

TEST(VisibilityOracleRobustness, DamagedHelmetLoadsAndAnswers) { checkModel("DamagedHelmet/DamagedHelmet.glb", 15000); }
TEST(VisibilityOracleRobustness, SuzanneLoadsAndAnswers) { checkModel("Suzanne/Suzanne.gltf", 2000); }

}  // namespace
