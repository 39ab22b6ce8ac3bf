// The shadow-view maths (passes/common shadow_views.h), GL-free: the split
// scheme, what each map covers (the camera's slices, the casters in front of
// them, a spot's cone, a cube's directions), the stabilised cascades'
// invariance (rotation: same radius; sub-texel translation: a static point
// keeps its sub-texel position) against the unstabilised baseline's shimmer,
// scenes at extreme scales, and the assignment strings.
#include "rgraph/passes/shadow_views.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"

namespace rgraph::shadows {
namespace {

constexpr float kAspect = 16.0f / 9.0f;

Scene shadowsScene() { return loadSceneFile(std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json"); }

glm::vec3 clipOf(const ShadowView& v, const glm::vec3& p) {
  const glm::vec4 c = v.proj * v.view * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

bool finite(const glm::mat4& m) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(m[i][j])) return false;
  return true;
}

// The camera frustum's corners between view depths d0 and d1, computed here
// from the camera's own view matrix (not the code under test's frame).
std::vector<glm::vec3> sliceCorners(const Camera& cam, float aspect, float d0, float d1) {
  const glm::mat4 toWorld = glm::inverse(cam.view());
  const float t = std::tan(glm::radians(cam.fovY) * 0.5f);
  std::vector<glm::vec3> out;
  for (float d : {d0, d1})
    for (float sx : {-1.0f, 1.0f})
      for (float sy : {-1.0f, 1.0f})
        out.push_back(glm::vec3(toWorld * glm::vec4(sx * d * t * aspect, sy * d * t, -d, 1.0f)));
  return out;
}

std::vector<glm::vec3> boxCorners(const Bounds& b) {
  std::vector<glm::vec3> out;
  for (int i = 0; i < 8; ++i)
    out.push_back({(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z});
  return out;
}

// The camera turned about its own position (yaw about +Y, then pitch).
Camera turned(Camera cam, float yawDeg, float pitchDeg) {
  const glm::vec3 f = cam.target - cam.position;
  glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(yawDeg), glm::vec3(0, 1, 0));
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(r * glm::vec4(f, 0)), glm::vec3(0, 1, 0)));
  r = glm::rotate(glm::mat4(1.0f), glm::radians(pitchDeg), right) * r;
  cam.target = cam.position + glm::vec3(r * glm::vec4(f, 0.0f));
  return cam;
}

std::vector<ShadowedLight> sunOnly(uint32_t cascades = 4) { return {{LightKind::directional, 0, 0, cascades}}; }

// ---------------------------------------------------------------- splits

TEST(CascadeSplits, UniformLogarithmicAndBetween) {
  const std::vector<float> uniform = cascadeSplits(1.0f, 101.0f, 4, 0.0f);
  EXPECT_EQ(uniform, (std::vector<float>{1, 26, 51, 76, 101}));
  const std::vector<float> logarithmic = cascadeSplits(1.0f, 16.0f, 4, 1.0f);
  ASSERT_EQ(logarithmic.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(logarithmic[i], std::pow(2.0f, float(i)), 1e-5f) << i;
  const std::vector<float> half = cascadeSplits(1.0f, 16.0f, 4, 0.5f);
  const std::vector<float> uni16 = cascadeSplits(1.0f, 16.0f, 4, 0.0f);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(half[i], 0.5f * (logarithmic[i] + uni16[i]), 1e-5f) << i;
  EXPECT_EQ(cascadeSplits(0.5f, 7.0f, 1, 0.75f), (std::vector<float>{0.5f, 7.0f}));
}

TEST(CascadeSplits, MonotonicWithExactEnds) {
  for (float lambda : {0.0f, 0.25f, 0.75f, 1.0f})
    for (uint32_t n = 1; n <= 4; ++n)
      for (auto [near, far] : {std::pair{0.1f, 80.0f}, std::pair{0.003f, 0.7f}, std::pair{10.0f, 1e6f}}) {
        const std::vector<float> s = cascadeSplits(near, far, n, lambda);
        ASSERT_EQ(s.size(), n + 1);
        EXPECT_EQ(s.front(), near);
        EXPECT_EQ(s.back(), far);
        for (size_t i = 1; i < s.size(); ++i) EXPECT_LT(s[i - 1], s[i]) << "lambda " << lambda << " n " << n;
      }
}

// ---------------------------------------------------------------- directional

TEST(DirectionalViews, CascadesCoverTheirSlicesAndFollowTheAssignment) {
  const Scene scene = shadowsScene();
  for (bool stabilize : {true, false})
    for (float yaw : {0.0f, 37.0f, 140.0f, 260.0f}) {
      const Camera cam = turned(scene.camera, yaw, yaw > 100.0f ? -20.0f : 10.0f);
      ShadowSettings settings;
      settings.stabilize = stabilize;
      const std::vector<ShadowView> views =
          shadowViews(scene, cam, kAspect, settings, {{LightKind::directional, 0, 3, 4}});
      ASSERT_EQ(views.size(), 4u);
      const std::vector<float> splits = cascadeSplits(cam.near, cam.far, 4, settings.lambda);
      for (uint32_t i = 0; i < 4; ++i) {
        const ShadowView& v = views[i];
        EXPECT_EQ(v.layer, 3 + i);
        EXPECT_EQ(v.cascade, i);
        EXPECT_EQ(v.kind, LightKind::directional);
        EXPECT_TRUE(v.depthClamp);
        EXPECT_EQ(v.splitNear, splits[i]);
        EXPECT_EQ(v.splitFar, splits[i + 1]);
        EXPECT_GT(v.texelWorld, 0.0f);
        for (const glm::vec3& c : sliceCorners(cam, kAspect, v.splitNear, v.splitFar)) {
          const glm::vec3 q = clipOf(v, c);
          EXPECT_LE(glm::abs(q.x), 1.0f + 1e-4f) << "cascade " << i << " stabilize " << stabilize;
          EXPECT_LE(glm::abs(q.y), 1.0f + 1e-4f) << "cascade " << i << " stabilize " << stabilize;
          EXPECT_LE(glm::abs(q.z), 1.0f + 1e-4f) << "cascade " << i << " stabilize " << stabilize;
        }
      }
    }
}

TEST(DirectionalViews, MaxDistanceEndsTheLastCascade) {
  const Scene scene = shadowsScene();
  ShadowSettings settings;
  settings.maxDistance = 30.0f;
  const std::vector<ShadowView> views = shadowViews(scene, scene.camera, kAspect, settings, sunOnly(3));
  ASSERT_EQ(views.size(), 3u);
  EXPECT_EQ(views.front().splitNear, scene.camera.near);
  EXPECT_EQ(views.back().splitFar, 30.0f);
  settings.maxDistance = 1000.0f;  // beyond camera.far: camera.far
  EXPECT_EQ(shadowViews(scene, scene.camera, kAspect, settings, sunOnly(3)).back().splitFar, scene.camera.far);
}

// A tall caster standing high above the view: its top lies between the sun
// and every cascade, far in front of any cascade's own depth range.
Scene withTower() {
  Scene scene = shadowsScene();
  Primitive tower = scene.primitives[1];
  tower.name = "tower";
  tower.bounds = Bounds{{-0.3f, 0.0f, -0.3f}, {0.3f, 60.0f, 0.3f}};
  scene.primitives.push_back(tower);
  return scene;
}

TEST(DirectionalViews, CastersBetweenTheSunAndACascadeAreInFrontOfTheNearPlane) {
  const Scene scene = withTower();
  for (bool stabilize : {true, false}) {
    ShadowSettings settings;
    settings.stabilize = stabilize;
    const std::vector<ShadowView> views = shadowViews(scene, scene.camera, kAspect, settings, sunOnly());
    int overlapping = 0;
    for (const ShadowView& v : views)
      for (const Primitive& p : scene.primitives) {
        if (!scene.castsShadows(p)) continue;
        // The caster's footprint in the map: does it overlap the cascade?
        glm::vec2 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& c : boxCorners(p.bounds)) {
          lo = glm::min(lo, glm::vec2(clipOf(v, c)));
          hi = glm::max(hi, glm::vec2(clipOf(v, c)));
        }
        if (hi.x < -1.0f || lo.x > 1.0f || hi.y < -1.0f || lo.y > 1.0f) continue;
        ++overlapping;
        for (const glm::vec3& c : boxCorners(p.bounds))
          EXPECT_GE(clipOf(v, c).z, -1.0f - 1e-4f)
              << p.name << " corner clipped by cascade " << v.cascade << "'s near plane, stabilize " << stabilize;
      }
    EXPECT_GT(overlapping, 4);
  }
}

TEST(DirectionalViews, StabilisedRadiusIgnoresCameraRotation) {
  const Scene scene = shadowsScene();
  ShadowSettings settings;
  const std::vector<ShadowView> base = shadowViews(scene, scene.camera, kAspect, settings, sunOnly());
  settings.stabilize = false;
  const std::vector<ShadowView> boxBase = shadowViews(scene, scene.camera, kAspect, settings, sunOnly());
  settings.stabilize = true;
  float boxChange = 0.0f;
  for (auto [yaw, pitch] : {std::pair{13.0f, 0.0f}, {90.0f, -30.0f}, {-171.0f, 25.0f}, {45.5f, 60.0f}}) {
    const Camera cam = turned(scene.camera, yaw, pitch);
    const std::vector<ShadowView> views = shadowViews(scene, cam, kAspect, settings, sunOnly());
    for (size_t i = 0; i < views.size(); ++i) {
      EXPECT_NEAR(views[i].texelWorld, base[i].texelWorld, 1e-5f * base[i].texelWorld) << "cascade " << i;
      EXPECT_NEAR(views[i].proj[0][0], base[i].proj[0][0], 1e-5f * base[i].proj[0][0]) << "cascade " << i;
      EXPECT_NEAR(views[i].proj[1][1], base[i].proj[1][1], 1e-5f * base[i].proj[1][1]) << "cascade " << i;
    }
    settings.stabilize = false;
    const std::vector<ShadowView> box = shadowViews(scene, cam, kAspect, settings, sunOnly());
    settings.stabilize = true;
    for (size_t i = 0; i < box.size(); ++i)
      boxChange = std::max(boxChange, std::abs(box[i].texelWorld / boxBase[i].texelWorld - 1.0f));
  }
  // The baseline's tight boxes change size as the camera turns (what makes
  // their edges crawl); the stabilised spheres do not.
  EXPECT_GT(boxChange, 0.02f);
}

// Sub-texel position of `p` in the map: the fraction of its texel coordinate.
glm::vec2 texelFraction(const ShadowView& v, const glm::vec3& p, uint32_t resolution) {
  const glm::vec2 t = (glm::vec2(clipOf(v, p)) + 1.0f) * (float(resolution) * 0.5f);
  return t - glm::floor(t);
}

float circularDistance(float a, float b) {
  const float d = std::abs(a - b);
  return std::min(d, 1.0f - d);
}

// The largest change of a static point's sub-texel position over 32 camera
// steps of 0.1 texel (of each cascade's own texel), per cascade.
std::vector<float> shimmer(const Scene& scene, const ShadowSettings& settings) {
  const std::vector<ShadowView> start = shadowViews(scene, scene.camera, kAspect, settings, sunOnly());
  std::vector<float> worst;
  const glm::vec3 stepDir = glm::normalize(glm::vec3(0.8f, 0.25f, -0.55f));
  for (size_t i = 0; i < start.size(); ++i) {
    const float mid = 0.5f * (start[i].splitNear + start[i].splitFar);
    const glm::vec3 point = scene.camera.position + scene.camera.forward() * mid;
    const glm::vec2 f0 = texelFraction(start[i], point, settings.resolution);
    float w = 0.0f;
    for (int step = 1; step <= 32; ++step) {
      Camera cam = scene.camera;
      const glm::vec3 offset = stepDir * (0.1f * float(step) * start[i].texelWorld);
      cam.position += offset;
      cam.target += offset;
      const ShadowView v = shadowViews(scene, cam, kAspect, settings, sunOnly())[i];
      const glm::vec3 q = clipOf(v, point);
      EXPECT_LE(std::max(std::abs(q.x), std::abs(q.y)), 1.0f) << "the point left cascade " << i;
      const glm::vec2 f = texelFraction(v, point, settings.resolution);
      w = std::max({w, circularDistance(f.x, f0.x), circularDistance(f.y, f0.y)});
    }
    worst.push_back(w);
  }
  return worst;
}

TEST(DirectionalViews, StabilisedCascadesMoveByWholeTexelsOnly) {
  const Scene scene = shadowsScene();
  ShadowSettings settings;
  const std::vector<float> stable = shimmer(scene, settings);
  settings.stabilize = false;
  const std::vector<float> baseline = shimmer(scene, settings);
  for (size_t i = 0; i < stable.size(); ++i) {
    std::printf("cascade %zu: largest sub-texel move of a static point over 32 steps of 0.1 texel: "
                "stabilised %.5f, unstabilised %.3f texel\n", i, stable[i], baseline[i]);
    EXPECT_LT(stable[i], 0.01f) << "cascade " << i << ": a static point moved by a fraction of a texel";
    // The baseline: the tight box follows the camera, so the point slides
    // across texels by ~0.1 texel a step (shimmer).
    EXPECT_GT(baseline[i], 0.05f) << "cascade " << i;
  }
}

// ---------------------------------------------------------------- spot and point

size_t firstLight(const Scene& scene, bool spot) {
  for (size_t i = 0; i < scene.pointLights.size(); ++i)
    if (scene.pointLights[i].spot == spot) return i;
  ADD_FAILURE() << "no " << (spot ? "spot" : "point") << " light";
  return 0;
}

float farthestCorner(const Scene& scene, const glm::vec3& from) {
  float d = 0.0f;
  for (const glm::vec3& c : boxCorners(scene.bounds())) d = std::max(d, glm::length(c - from));
  return d;
}

void expectConeInside(const Scene& scene, uint32_t index, uint32_t resolution) {
  const PointLight& l = scene.pointLights[index];
  ShadowSettings settings;
  settings.resolution = resolution;
  const std::vector<ShadowView> views =
      shadowViews(scene, scene.camera, kAspect, settings, {{LightKind::spot, index, 7, 1}});
  ASSERT_EQ(views.size(), 1u);
  const ShadowView& v = views[0];
  EXPECT_EQ(v.layer, 7u);
  EXPECT_FALSE(v.depthClamp);
  EXPECT_EQ(v.lightPosition, l.position);
  const float reach = std::min(l.radius > 0.0f ? l.radius : lightRadius(l), farthestCorner(scene, l.position));
  EXPECT_NEAR(v.farPlane, reach, 1e-5f * reach);
  EXPECT_GT(v.nearPlane, 0.0f);
  EXPECT_LT(v.nearPlane, 0.01f * v.farPlane);
  const glm::vec3 u = glm::normalize(glm::cross(l.direction, std::abs(l.direction.x) < 0.9f ? glm::vec3(1, 0, 0)
                                                                                              : glm::vec3(0, 1, 0)));
  const glm::vec3 w = glm::cross(l.direction, u);
  const float outer = glm::radians(l.outerConeDeg);
  for (int k = 0; k < 64; ++k) {
    const float phi = glm::two_pi<float>() * float(k) / 64.0f;
    const glm::vec3 rim = std::cos(outer) * l.direction + std::sin(outer) * (std::cos(phi) * u + std::sin(phi) * w);
    // Along the rim: at the reach, half way, and just beyond the near plane.
    for (float s : {0.999f * v.farPlane, 0.5f * v.farPlane, 2.0f * v.nearPlane / std::cos(outer)}) {
      const glm::vec3 q = clipOf(v, l.position + s * rim);
      // Inside, with the margin kept for a filter kernel (4 texels; 3 asserted).
      EXPECT_LE(std::max(std::abs(q.x), std::abs(q.y)), 1.0f - 6.0f / float(resolution)) << "rim " << k;
      EXPECT_GT(q.z, -1.0f);
      EXPECT_LT(q.z, 1.0f);
    }
  }
}

TEST(SpotViews, TheConeToItsReachIsInside) {
  Scene scene = shadowsScene();
  for (uint32_t i = 0; i < scene.pointLights.size(); ++i)
    if (scene.pointLights[i].spot) {
      expectConeInside(scene, i, 2048);
      expectConeInside(scene, i, 256);
    }
  // A narrow and a wide cone.
  const size_t s = firstLight(scene, true);
  scene.pointLights[s].outerConeDeg = 3.0f;
  expectConeInside(scene, uint32_t(s), 1024);
  scene.pointLights[s].outerConeDeg = 80.0f;
  expectConeInside(scene, uint32_t(s), 1024);
}

TEST(SpotViews, AHemisphereConeIsCappedBelow170Degrees) {
  Scene scene = shadowsScene();
  const size_t s = firstLight(scene, true);
  scene.pointLights[s].outerConeDeg = 90.0f;
  scene.pointLights[s].direction = glm::vec3(0, -1, 0);  // straight down: the up vector must not be parallel
  const ShadowView v = shadowViews(scene, scene.camera, kAspect, {}, {{LightKind::spot, uint32_t(s), 0, 1}})[0];
  EXPECT_TRUE(finite(v.view) && finite(v.proj));
  const float halfFov = std::atan(1.0f / v.proj[1][1]);
  EXPECT_LT(2.0f * glm::degrees(halfFov), 170.0f + 1e-3f);
  EXPECT_GT(2.0f * glm::degrees(halfFov), 169.0f);
  // The axis still points down the cone.
  const glm::vec3 q = clipOf(v, scene.pointLights[s].position + glm::vec3(0, -1, 0));
  EXPECT_NEAR(q.x, 0.0f, 1e-5f);
  EXPECT_NEAR(q.y, 0.0f, 1e-5f);
}

// GL's cube-map face selection and face coordinates (OpenGL 4.5, table
// 8.19): the face the largest |component| picks, and (sc, tc) / |ma| there.
struct CubeLookup {
  uint32_t face;
  glm::vec2 st;  // -1..1
};

CubeLookup glCubeLookup(const glm::vec3& r) {
  const glm::vec3 a = glm::abs(r);
  if (a.x >= a.y && a.x >= a.z)
    return r.x > 0 ? CubeLookup{0, glm::vec2(-r.z, -r.y) / a.x} : CubeLookup{1, glm::vec2(r.z, -r.y) / a.x};
  if (a.y >= a.z) return r.y > 0 ? CubeLookup{2, glm::vec2(r.x, r.z) / a.y} : CubeLookup{3, glm::vec2(r.x, -r.z) / a.y};
  return r.z > 0 ? CubeLookup{4, glm::vec2(r.x, -r.y) / a.z} : CubeLookup{5, glm::vec2(-r.x, -r.y) / a.z};
}

void expectCubeMatchesLookups(const Scene& scene, uint32_t index) {
  const PointLight& l = scene.pointLights[index];
  const std::vector<ShadowView> views =
      shadowViews(scene, scene.camera, kAspect, {}, {{LightKind::point, index, 2, 6}});
  ASSERT_EQ(views.size(), 6u);
  for (uint32_t f = 0; f < 6; ++f) {
    EXPECT_EQ(views[f].layer, 2 + f);
    EXPECT_EQ(views[f].cascade, f);
    EXPECT_TRUE(finite(views[f].view) && finite(views[f].proj));
    EXPECT_NEAR(views[f].texelWorld, 2.0f / 2048.0f, 1e-7f);  // 2 tan(45 deg) / resolution
  }
  std::mt19937 rng(7);
  std::normal_distribution<float> n;
  int tested = 0;
  while (tested < 500) {
    const glm::vec3 d = glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    const glm::vec3 a = glm::abs(d);
    const float major = std::max({a.x, a.y, a.z});
    const float second = a.x + a.y + a.z - major - std::min({a.x, a.y, a.z});
    if (major - second < 1e-3f) continue;  // on a face's edge: either face will do
    ++tested;
    const glm::vec3 p = l.position + d * (0.5f * views[0].farPlane);
    const CubeLookup lookup = glCubeLookup(d);
    int inside = 0;
    for (uint32_t f = 0; f < 6; ++f) {
      const glm::vec3 q = clipOf(views[f], p);
      const bool in = -(views[f].view * glm::vec4(p, 1)).z > 0 && std::abs(q.x) <= 1 && std::abs(q.y) <= 1 &&
                      std::abs(q.z) <= 1;
      inside += in;
      if (f == lookup.face) {
        EXPECT_TRUE(in) << "face " << f;
        // The face drew the point where a cube lookup along d reads it.
        EXPECT_NEAR(q.x, lookup.st.x, 1e-4f) << "face " << f;
        EXPECT_NEAR(q.y, lookup.st.y, 1e-4f) << "face " << f;
      }
    }
    EXPECT_EQ(inside, 1);
  }
}

TEST(PointViews, EachDirectionFallsInTheFaceACubeLookupPicks) {
  const Scene scene = shadowsScene();
  for (uint32_t i = 0; i < scene.pointLights.size(); ++i)
    if (!scene.pointLights[i].spot) expectCubeMatchesLookups(scene, i);
}

TEST(PointViews, ALightInsideTheSceneAndOneFarOutside) {
  Scene scene = shadowsScene();
  const uint32_t p = uint32_t(firstLight(scene, false));
  PointLight& l = scene.pointLights[p];
  ASSERT_TRUE(glm::all(glm::greaterThan(l.position, scene.bounds().min)) &&
              glm::all(glm::lessThan(l.position, scene.bounds().max)));
  const float inside = shadowViews(scene, scene.camera, kAspect, {}, {{LightKind::point, p, 0, 6}})[0].farPlane;
  EXPECT_NEAR(inside, std::min(lightRadius(l), farthestCorner(scene, l.position)), 1e-4f * inside);
  // No falloff, 500 units away: the reach is the scene's farthest corner.
  l.position = glm::vec3(300.0f, 250.0f, -300.0f);
  l.linear = l.quadratic = 0.0f;
  l.radius = 0.0f;
  ASSERT_TRUE(std::isinf(lightRadius(l)));
  const std::vector<ShadowView> views = shadowViews(scene, scene.camera, kAspect, {}, {{LightKind::point, p, 0, 6}});
  for (const ShadowView& v : views) {
    EXPECT_TRUE(finite(v.view) && finite(v.proj));
    EXPECT_NEAR(v.farPlane, farthestCorner(scene, l.position), 1e-4f * v.farPlane);
    EXPECT_GT(v.nearPlane, 0.0f);
  }
  expectCubeMatchesLookups(scene, p);
}

// ---------------------------------------------------------------- scales

// The shadows scene scaled by s (geometry, lights' reach, camera), with a
// shadowed point light.
Scene scaledScene(float s) {
  Scene scene;
  Scene src = shadowsScene();
  const Camera cam = src.camera;
  appendScene(scene, std::move(src), glm::scale(glm::mat4(1.0f), glm::vec3(s)));
  for (PointLight& l : scene.pointLights) l.radius = s * lightRadius(l);
  scene.camera = cam;
  scene.camera.position *= s;
  scene.camera.target *= s;
  scene.camera.near *= s;
  scene.camera.far *= s;
  return scene;
}

TEST(ShadowViewsScale, HugeAndTinyScenesGiveFiniteMatricesThatStillCover) {
  const Scene unit = scaledScene(1.0f);
  const uint32_t spot = uint32_t(firstLight(unit, true)), point = uint32_t(firstLight(unit, false));
  const std::vector<ShadowedLight> lights = {{LightKind::directional, 0, 0, 4},
                                             {LightKind::spot, spot, 4, 1},
                                             {LightKind::point, point, 5, 6}};
  const std::vector<ShadowView> ref = shadowViews(unit, unit.camera, kAspect, {}, lights);
  for (float s : {1e4f, 1e-3f}) {
    const Scene scene = scaledScene(s);
    const std::vector<ShadowView> views = shadowViews(scene, scene.camera, kAspect, {}, lights);
    ASSERT_EQ(views.size(), 11u);
    for (size_t i = 0; i < views.size(); ++i) {
      const ShadowView& v = views[i];
      EXPECT_TRUE(finite(v.view) && finite(v.proj)) << "scale " << s << " layer " << v.layer;
      if (v.kind == LightKind::directional) {
        // Same cascades at another scale: texels scale with it (the radius's
        // rounding to 1/16 of its power of two differs by at most 1/16).
        EXPECT_NEAR(v.texelWorld / (s * ref[i].texelWorld), 1.0f, 0.07f) << "scale " << s;
        for (const glm::vec3& c : sliceCorners(scene.camera, kAspect, v.splitNear, v.splitFar)) {
          const glm::vec3 q = clipOf(v, c);
          EXPECT_LE(std::max({std::abs(q.x), std::abs(q.y), std::abs(q.z)}), 1.0f + 1e-3f) << "scale " << s;
        }
      } else {
        EXPECT_NEAR(v.farPlane / (s * ref[i].farPlane), 1.0f, 1e-3f) << "scale " << s;
        EXPECT_NEAR(v.nearPlane / (s * ref[i].nearPlane), 1.0f, 1e-3f) << "scale " << s;
        EXPECT_EQ(v.texelWorld, ref[i].texelWorld);  // an angle: no scale
      }
    }
  }
}

// ---------------------------------------------------------------- all lights together

TEST(ShadowViewsOrder, ViewsComeInLayerOrderWithTheirLights) {
  const Scene scene = shadowsScene();
  const uint32_t spot = uint32_t(firstLight(scene, true)), point = uint32_t(firstLight(scene, false));
  const std::vector<ShadowView> views = shadowViews(
      scene, scene.camera, kAspect, {},
      {{LightKind::point, point, 5, 6}, {LightKind::directional, 0, 1, 4}, {LightKind::spot, spot, 0, 1}});
  ASSERT_EQ(views.size(), 11u);
  for (uint32_t i = 0; i < 11; ++i) EXPECT_EQ(views[i].layer, i);
  EXPECT_EQ(views[0].kind, LightKind::spot);
  EXPECT_EQ(views[0].light, spot);
  EXPECT_EQ(views[1].kind, LightKind::directional);
  EXPECT_EQ(views[4].cascade, 3u);
  EXPECT_EQ(views[5].kind, LightKind::point);
  EXPECT_EQ(views[10].cascade, 5u);
  EXPECT_EQ(views[10].light, point);
}

TEST(ShadowViewsErrors, LightsTheSceneDoesNotHave) {
  const Scene scene = shadowsScene();
  const uint32_t spot = uint32_t(firstLight(scene, true)), point = uint32_t(firstLight(scene, false));
  auto message = [&](const ShadowedLight& l) {
    try {
      shadowViews(scene, scene.camera, kAspect, {}, {l});
    } catch (const RuntimeError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({LightKind::directional, 3, 0, 4}),
            "shadow views: directional light 3 does not exist (the scene has 1)");
  EXPECT_NE(message({LightKind::point, 99, 0, 6}).find("point light 99 does not exist"), std::string::npos);
  EXPECT_EQ(message({LightKind::spot, point, 0, 1}), "shadow views: light " + std::to_string(point) +
                                                         " is assigned as a spot light but is a point light");
  EXPECT_EQ(message({LightKind::point, spot, 0, 6}), "shadow views: light " + std::to_string(spot) +
                                                         " is assigned as a point light but is a spot light");
}

// ---------------------------------------------------------------- footprint

TEST(TexelFootprint, OrthoIsConstantPerspectiveGrowsWithAxialDistance) {
  const Scene scene = shadowsScene();
  const uint32_t spot = uint32_t(firstLight(scene, true));
  ShadowSettings settings;
  settings.resolution = 1024;
  const std::vector<ShadowView> views = shadowViews(scene, scene.camera, kAspect, settings,
                                                    {{LightKind::directional, 0, 0, 2}, {LightKind::spot, spot, 2, 1}});
  const ShadowView& cascade = views[0];
  EXPECT_NEAR(texelFootprint(cascade, glm::vec3(0), 1024), cascade.texelWorld, 1e-6f * cascade.texelWorld);
  EXPECT_NEAR(texelFootprint(cascade, glm::vec3(5, 1, -3), 1024), cascade.texelWorld, 1e-6f * cascade.texelWorld);
  EXPECT_NEAR(texelFootprint(cascade, glm::vec3(0), 2048), 0.5f * cascade.texelWorld, 1e-6f * cascade.texelWorld);
  ASSERT_EQ(views.size(), 3u);
  const ShadowView& s = views[2];
  const PointLight& l = scene.pointLights[spot];
  const glm::vec3 side = glm::normalize(glm::cross(l.direction, glm::vec3(1, 0, 0)));
  // 3 units along the axis, and 1 unit off it: the axial distance counts.
  EXPECT_NEAR(texelFootprint(s, l.position + 3.0f * l.direction, 1024), 3.0f * s.texelWorld, 1e-4f * s.texelWorld);
  EXPECT_NEAR(texelFootprint(s, l.position + 3.0f * l.direction + side, 1024), 3.0f * s.texelWorld,
              1e-4f * s.texelWorld);
  EXPECT_NEAR(texelFootprint(s, l.position + 3.0f * l.direction, 512), 6.0f * s.texelWorld, 1e-4f * s.texelWorld);
}

// ---------------------------------------------------------------- assignment strings

TEST(AssignmentString, RoundTrips) {
  const std::vector<ShadowedLight> lights = {{LightKind::directional, 0, 0, 4},
                                             {LightKind::spot, 1, 4, 1},
                                             {LightKind::point, 3, 5, 6},
                                             {LightKind::directional, 4294967295u, 11, 1}};
  EXPECT_EQ(encode(lights), "d0:0+4 s1:4+1 p3:5+6 d4294967295:11+1");
  EXPECT_EQ(decode(encode(lights)), lights);
  EXPECT_EQ(decode("  d0:0+4   s1:4+1 "), (std::vector<ShadowedLight>{lights[0], lights[1]}));
  EXPECT_TRUE(decode("").empty());
  EXPECT_TRUE(decode("   ").empty());
  EXPECT_EQ(encode({}), "");
}

TEST(AssignmentString, MalformedTokensAreNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"x0:0+4", "'x0:0+4': unknown light kind 'x' (d, s or p)"},
      {"d0", "'d0': missing ':<first layer>'"},
      {"d0:0", "'d0:0': missing '+<layer count>'"},
      {"d:0+4", "'d:0+4': missing light index"},
      {"d0:+4", "'d0:+4': missing first layer"},
      {"d0:0+", "'d0:0+': missing layer count"},
      {"da:0+4", "'da:0+4': light index 'a' is not a number"},
      {"d0:-1+4", "'d0:-1+4': first layer '-1' is not a number"},
      {"d0:0+4x", "'d0:0+4x': layer count '4x' is not a number"},
      {"d4294967296:0+4", "'d4294967296:0+4': light index '4294967296' is out of range (at most 4294967295)"},
      {"d0:99999999999999999999999+4", "first layer '99999999999999999999999' is out of range"},
      {"d0:0+0", "'d0:0+0': layer count must be at least 1"},
      {"d0:0+5", "'d0:0+5': a directional light has 1 to 4 cascades, got 5"},
      {"s1:0+2", "'s1:0+2': a spot light has 1 layer, got 2"},
      {"p3:0+5", "'p3:0+5': a point light has 6 layers (cube faces), got 5"},
      {"p3:0+7", "'p3:0+7': a point light has 6 layers (cube faces), got 7"},
      {"p0:4294967290+6", "'p0:4294967290+6': its layers end beyond layer 4294967295"},
      {"d0:0+4 q1:4+1", "'q1:4+1': unknown light kind 'q'"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      decode(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const RuntimeError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("shadow assignment '", 0), 0u) << m;
      EXPECT_NE(m.find(expected), std::string::npos) << "got: " << m;
    }
  }
}

}  // namespace
}  // namespace rgraph::shadows
