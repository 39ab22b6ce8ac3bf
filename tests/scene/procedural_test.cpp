// Procedural scenes, the PRNG, light radii and camera helpers.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "rgraph/error.h"
#include "rgraph/scene.h"

using namespace rgraph;

TEST(LightRadius, MatchesTheChaptersFormula) {
  PointLight l;
  l.color = glm::vec3(1.0f);
  l.intensity = 1.0f;
  l.constant = 1.0f;
  l.linear = 0.7f;
  l.quadratic = 1.8f;
  const double hand = (-0.7 + std::sqrt(0.49 - 4.0 * 1.8 * (1.0 - 256.0 / 5.0))) / (2.0 * 1.8);
  EXPECT_NEAR(lightRadius(l, 5.0f / 256.0f), hand, 1e-5);
  EXPECT_NEAR(lightRadius(l), hand, 1e-5);  // the default threshold is 5/256
  EXPECT_NEAR(hand, 5.0901, 1e-3);
  // The attenuation at the radius is exactly the threshold.
  const float r = lightRadius(l);
  EXPECT_NEAR(1.0f / (l.constant + l.linear * r + l.quadratic * r * r), 5.0f / 256.0f, 1e-5f);
  // The brightest channel times the intensity drives it.
  PointLight dim = l;
  dim.color = glm::vec3(0.2f, 0.5f, 0.1f);
  const double handDim = (-0.7 + std::sqrt(0.49 - 4.0 * 1.8 * (1.0 - 0.5 * 256.0 / 5.0))) / (2.0 * 1.8);
  EXPECT_NEAR(lightRadius(dim), handDim, 1e-5);
  dim.intensity = 2.0f;
  EXPECT_NEAR(lightRadius(dim), hand, 1e-5);
}

TEST(LightRadius, DegenerateAttenuation) {
  PointLight l;
  l.color = glm::vec3(1.0f);
  l.constant = 1.0f;
  l.quadratic = 0.0f;
  l.linear = 0.5f;
  EXPECT_NEAR(lightRadius(l), (256.0f / 5.0f - 1.0f) / 0.5f, 1e-3f);  // linear only
  l.linear = 0.0f;
  EXPECT_EQ(lightRadius(l), std::numeric_limits<float>::infinity());  // no falloff
  l.linear = 0.7f;
  l.quadratic = 1.8f;
  l.color = glm::vec3(0.0f);
  EXPECT_EQ(lightRadius(l), 0.0f);  // black light
  l.color = glm::vec3(1.0f);
  l.constant = 100.0f;
  EXPECT_EQ(lightRadius(l), 0.0f);  // never reaches the threshold
}

TEST(GlibcRandom, Deterministic) {
  GlibcRandom a(13), b(13), c(14);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const int x = a.next();
    EXPECT_EQ(x, b.next());
    if (x != c.next()) differs = true;
    ASSERT_GE(x, 0);
  }
  EXPECT_TRUE(differs);
  // glibc: srand(1) then rand() begins 1804289383, 846930886, 1681692777.
  GlibcRandom one(1);
  EXPECT_EQ(one.next(), 1804289383);
  EXPECT_EQ(one.next(), 846930886);
  EXPECT_EQ(one.next(), 1681692777);
}

#ifdef __GLIBC__
// Where the C library is glibc, the reimplementation matches it exactly.
TEST(GlibcRandom, MatchesGlibcRand) {
  for (unsigned seed : {0u, 1u, 13u, 12345u, 2147483647u, 4000000000u}) {
    std::srand(seed);
    GlibcRandom r(seed);
    for (int i = 0; i < 2000; ++i) ASSERT_EQ(r.next(), std::rand()) << "seed " << seed << " draw " << i;
  }
}
#endif

TEST(LearnOpenGLScene, ObjectsLightsAndCamera) {
  const Scene s = makeLearnOpenGLScene();
  EXPECT_NO_THROW(s.validate());
  ASSERT_EQ(s.primitives.size(), 9u);
  const float xz[3] = {-3.0f, 0.0f, 3.0f};
  for (int k = 0; k < 9; ++k) {
    const Primitive& p = s.primitives[size_t(k)];
    const glm::vec3 expected(xz[k % 3], -0.5f, xz[k / 3]);  // the chapter's objectPositions order
    EXPECT_NEAR(glm::distance(glm::vec3(p.transform[3]), expected), 0.0f, 1e-6f) << k;
    EXPECT_NEAR(glm::distance(p.bounds.center(), expected), 0.0f, 1e-5f) << k;
    EXPECT_NEAR(p.bounds.size().x, 1.0f, 1e-5f);  // [-1,1] model scaled 0.5
    EXPECT_NEAR(p.bounds.size().y, 1.0f, 1e-5f);
  }
  ASSERT_EQ(s.pointLights.size(), 32u);
  EXPECT_TRUE(s.hasPointLights());
  EXPECT_TRUE(s.directionalLights.empty());
  const double hand = (-0.7 + std::sqrt(0.49 - 4.0 * 1.8 * (1.0 - 256.0 / 5.0))) / (2.0 * 1.8);
  for (const PointLight& l : s.pointLights) {
    EXPECT_GE(l.position.x, -3.0f);
    EXPECT_LT(l.position.x, 3.0f);
    EXPECT_GE(l.position.y, -4.0f);
    EXPECT_LT(l.position.y, 2.0f);
    EXPECT_GE(l.position.z, -3.0f);
    EXPECT_LT(l.position.z, 3.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(l.color[c], 0.5f);
      EXPECT_LT(l.color[c], 1.0f);
    }
    EXPECT_EQ(l.constant, 1.0f);
    EXPECT_EQ(l.linear, 0.7f);
    EXPECT_EQ(l.quadratic, 1.8f);
    EXPECT_EQ(l.radius, lightRadius(l));
    EXPECT_LE(l.radius, hand + 1e-5);  // colours <= 1: never larger than the white light's
    EXPECT_GT(l.radius, 1.5f);
  }
  // Same positions on every run (and on every platform: no std::rand).
  const Scene again = makeLearnOpenGLScene();
  for (size_t i = 0; i < 32; ++i) {
    EXPECT_EQ(s.pointLights[i].position, again.pointLights[i].position);
    EXPECT_EQ(s.pointLights[i].color, again.pointLights[i].color);
  }
  // The chapter's code: srand(13), then per light x, y, z, r, g, b from rand().
  GlibcRandom rng(13);
  const float x0 = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
  const float y0 = float(((rng.next() % 100) / 100.0) * 6.0 - 4.0);
  const float z0 = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
  EXPECT_EQ(s.pointLights[0].position, glm::vec3(x0, y0, z0));

  EXPECT_EQ(s.ambient, glm::vec3(0.1f));
  ASSERT_TRUE(s.hasCamera);
  EXPECT_EQ(s.camera.position, glm::vec3(0, 0, 5));
  EXPECT_EQ(s.camera.forward(), glm::vec3(0, 0, -1));
  EXPECT_EQ(s.camera.fovY, 45.0f);
  EXPECT_EQ(s.camera.near, 0.1f);
  EXPECT_EQ(s.camera.far, 100.0f);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].specular, 0.5f);
  EXPECT_TRUE(s.materials[0].baseColorTexture.valid());
  EXPECT_FALSE(s.hasBlendMaterials());
  EXPECT_FALSE(s.hasNormalMaps());
  EXPECT_FALSE(s.hasMetallicRoughnessVariation());
}

TEST(LearnOpenGLScene, FixedLightPositions) {
  // Regression values: the chapter's srand(13) sequence as glibc produces it.
  const Scene s = makeLearnOpenGLScene();
  GlibcRandom rng(13);
  for (size_t i = 0; i < 32; ++i) {
    glm::vec3 p, c;
    p.x = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
    p.y = float(((rng.next() % 100) / 100.0) * 6.0 - 4.0);
    p.z = float(((rng.next() % 100) / 100.0) * 6.0 - 3.0);
    c.r = float(((rng.next() % 100) / 200.0f) + 0.5);
    c.g = float(((rng.next() % 100) / 200.0f) + 0.5);
    c.b = float(((rng.next() % 100) / 200.0f) + 0.5);
    EXPECT_EQ(s.pointLights[i].position, p) << i;
    EXPECT_EQ(s.pointLights[i].color, c) << i;
  }
}

TEST(ManyLightsScene, TenThousandLights) {
  const Scene s = makeManyLightsScene(10000);
  EXPECT_NO_THROW(s.validate());
  ASSERT_EQ(s.pointLights.size(), 10000u);
  const Bounds b = s.bounds();
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const PointLight& l : s.pointLights) {
    ASSERT_TRUE(std::isfinite(l.radius));
    ASSERT_GT(l.radius, 0.0f);
    ASSERT_NEAR(l.radius, lightRadius(l), 1e-4f * l.radius);
    ASSERT_GE(l.position.x, b.min.x);
    ASSERT_LE(l.position.x, b.max.x);
    ASSERT_GE(l.position.z, b.min.z);
    ASSERT_LE(l.position.z, b.max.z);
    ASSERT_GT(l.position.y, 0.0f);
    lo = glm::min(lo, l.position);
    hi = glm::max(hi, l.position);
  }
  // Spread over the field: the lights cover most of the floor.
  EXPECT_GT(hi.x - lo.x, 0.8f * (b.max.x - b.min.x));
  EXPECT_GT(hi.z - lo.z, 0.8f * (b.max.z - b.min.z));
  EXPECT_GT(s.primitives.size(), 30u);
  EXPECT_LT(s.triangleCount(), 200000u);
  ASSERT_TRUE(s.hasCamera);
  EXPECT_GT(s.camera.position.y, 0.0f);
  EXPECT_GT(s.camera.far, glm::length(s.camera.position) + b.radius());
}

TEST(ManyLightsScene, SeededAndSized) {
  const Scene a = makeManyLightsScene(64, 7), b = makeManyLightsScene(64, 7), c = makeManyLightsScene(64, 8);
  ASSERT_EQ(a.pointLights.size(), 64u);
  bool differs = false;
  for (size_t i = 0; i < 64; ++i) {
    EXPECT_EQ(a.pointLights[i].position, b.pointLights[i].position);
    if (a.pointLights[i].position != c.pointLights[i].position) differs = true;
  }
  EXPECT_TRUE(differs);
  EXPECT_TRUE(makeManyLightsScene(0).pointLights.empty());
  EXPECT_THROW(makeManyLightsScene(-1), RuntimeError);
  EXPECT_THROW(makeManyLightsScene(100001), RuntimeError);
  // Denser lights get smaller volumes.
  EXPECT_GT(makeManyLightsScene(32).pointLights[0].radius, makeManyLightsScene(4096).pointLights[0].radius);
}

TEST(ManyLightsScene, PillarsVariantKeepsTheFieldAndAddsDepthDiscontinuities) {
  const Scene field = makeManyLightsScene(256, 3), pillars = makeManyLightsPillarsScene(256, 3);
  EXPECT_EQ(pillars.source, "many-lights:256:pillars");
  ASSERT_EQ(pillars.pointLights.size(), field.pointLights.size());
  for (size_t i = 0; i < field.pointLights.size(); ++i)
    EXPECT_EQ(pillars.pointLights[i].position, field.pointLights[i].position);
  // The field's primitives, a far wall and 7 pillars.
  ASSERT_EQ(pillars.primitives.size(), field.primitives.size() + 8);
  const Camera& cam = pillars.camera;
  const glm::mat4 view = cam.view();
  auto depth = [&](const Bounds& b) { return -(view * glm::vec4(b.center(), 1.0f)).z; };
  float wallDepth = 0, nearestPillar = 1e30f, farthestPillar = 0;
  int pillarCount = 0;
  for (const Primitive& p : pillars.primitives) {
    if (p.name == "far_wall") wallDepth = depth(p.bounds);
    if (p.name.rfind("pillar", 0) == 0) {
      ++pillarCount;
      nearestPillar = std::min(nearestPillar, depth(p.bounds));
      farthestPillar = std::max(farthestPillar, depth(p.bounds));
      // Taller than the view at their distance: they cross the whole frame.
      EXPECT_GT(p.bounds.max.y, cam.position.y + depth(p.bounds) * std::tan(glm::radians(cam.fovY * 0.5f)));
    }
  }
  EXPECT_EQ(pillarCount, 7);
  // Pillars close to the camera, the wall at the far end: a 2D tile over a
  // pillar's edge spans more than 5x in depth.
  EXPECT_GT(nearestPillar, cam.near);
  EXPECT_GT(wallDepth, 5.0f * farthestPillar);
  EXPECT_LT(wallDepth, cam.far);
}

TEST(LoadSceneAny, ProceduralSpecs) {
  EXPECT_EQ(loadSceneAny("learnopengl").pointLights.size(), 32u);
  EXPECT_EQ(loadSceneAny("many-lights:10000").pointLights.size(), 10000u);
  EXPECT_EQ(loadSceneAny("many-lights:16:3").pointLights[0].position, makeManyLightsScene(16, 3).pointLights[0].position);
  EXPECT_EQ(loadSceneAny("many-lights:16:pillars").source, "many-lights:16:pillars");
  EXPECT_EQ(loadSceneAny("many-lights:16:3:pillars").primitives.size(), makeManyLightsPillarsScene(16, 3).primitives.size());
  EXPECT_EQ(loadSceneAny("many-lights:16:3:pillars").pointLights[0].position,
            makeManyLightsScene(16, 3).pointLights[0].position);
  for (const char* bad : {"many-lights:", "many-lights:pillars", "many-lights::pillars", "many-lights:16:pillars:3",
                          "many-lights:16:x:pillars", "many-lights:abc", "many-lights:-5", "many-lights:100001", "many-lights:10:x",
                          "nonsense", "model.obj", ""}) {
    EXPECT_THROW(loadSceneAny(bad), RuntimeError) << bad;
  }
  try {
    loadSceneAny("model.obj");
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("model.obj"), std::string::npos);
  }
}

TEST(Camera, ViewAndProjection) {
  Camera c;
  c.position = glm::vec3(0, 0, 5);
  c.target = glm::vec3(0, 0, 0);
  const glm::vec4 v = c.view() * glm::vec4(0, 0, 0, 1);
  EXPECT_NEAR(glm::distance(glm::vec3(v), glm::vec3(0, 0, -5)), 0.0f, 1e-5f);
  const glm::mat4 p = c.projection(16.0f / 9.0f);
  glm::vec4 nearPt = p * glm::vec4(0, 0, -c.near, 1);
  glm::vec4 farPt = p * glm::vec4(0, 0, -c.far, 1);
  EXPECT_NEAR(nearPt.z / nearPt.w, -1.0f, 1e-4f);
  EXPECT_NEAR(farPt.z / farPt.w, 1.0f, 1e-4f);
  // The top of the vertical fov maps to y = 1.
  const float h = std::tan(glm::radians(c.fovY * 0.5f)) * 10.0f;
  glm::vec4 top = p * glm::vec4(0, h, -10, 1);
  EXPECT_NEAR(top.y / top.w, 1.0f, 1e-4f);
  // Looking straight down does not break lookAt.
  c.target = glm::vec3(0, -10, 5);
  const glm::mat4 down = c.view();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(down[i][j]));
}

TEST(Camera, FrameBoundsSeesEverything) {
  Bounds b;
  b.expand(glm::vec3(-10, 0, -2));
  b.expand(glm::vec3(30, 5, 8));
  const Camera c = frameBounds(b, 45.0f);
  const glm::mat4 vp = c.viewProjection(1.0f);
  for (int i = 0; i < 8; ++i) {
    glm::vec4 p = vp * glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z, 1.0f);
    ASSERT_GT(p.w, 0.0f);
    p /= p.w;
    EXPECT_LE(std::abs(p.x), 1.0f);
    EXPECT_LE(std::abs(p.y), 1.0f);
    EXPECT_LE(std::abs(p.z), 1.0f);
  }
}

// The default camera frames the bounding sphere of the drawn vertices, not
// the box's: a sphere's box diagonal is sqrt(3) times its radius, and a
// model framed by it fills about half the frame's height.
TEST(CameraHelpers, BoundingSphereReachesTheFarthestVertexOnly) {
  Scene s;
  s.meshes.push_back(makeUvSphere(2.0f));
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.transform = glm::mat4(1.0f);
  p.transform[3] = glm::vec4(5.0f, 0.0f, 0.0f, 1.0f);
  p.bounds = s.meshes[0].bounds.transformed(p.transform);
  s.primitives.push_back(p);
  const Scene::Sphere sphere = s.boundingSphere();
  EXPECT_NEAR(sphere.center.x, 5.0f, 1e-4f);
  EXPECT_NEAR(sphere.radius, 2.0f, 1e-3f);            // the box's radius is 2 sqrt(3)
  EXPECT_GT(s.bounds().radius(), 1.7f * sphere.radius);
  EXPECT_EQ(Scene{}.boundingSphere().radius, 0.0f);
}

// What rgraph render shows for a model without a camera: every vertex in
// view, and the model's larger extent across 95% of the frame's short side
// (the sphere framing alone: Suzanne 0.65 of the height, Box 0.66).
TEST(CameraHelpers, DefaultCameraFillsTheShortSide) {
  for (const char* model : {"Suzanne/Suzanne.gltf", "DamagedHelmet/DamagedHelmet.glb", "Box/Box.glb",
                            "LightsPunctualLamp/LightsPunctualLamp.gltf"}) {
    Scene s = loadGltf(std::string(RGRAPH_ASSETS_DIR) + "/gltf/" + model);
    s.hasCamera = false;
    applySceneDefaults(s);
    const glm::mat4 vp = s.camera.viewProjection(1.0f);  // a square: the short side both ways
    float extentX = 0.0f, extentY = 0.0f;
    for (const Primitive& p : s.primitives)
      for (const glm::vec3& v : s.meshes[p.mesh].positions) {
        glm::vec4 c = vp * p.transform * glm::vec4(v, 1.0f);
        ASSERT_GT(c.w, 0.0f) << model;
        c /= c.w;
        EXPECT_LE(std::abs(c.x), 0.951f) << model;
        EXPECT_LE(std::abs(c.y), 0.951f) << model;
        EXPECT_LE(std::abs(c.z), 1.0f) << model << ": outside the near or far plane";
        extentX = std::max(extentX, std::abs(c.x));
        extentY = std::max(extentY, std::abs(c.y));
      }
    EXPECT_NEAR(std::max(extentX, extentY), 0.95f, 1e-3f) << model;
    std::printf("%s reaches %.3f of the half width, %.3f of the half height\n", model, double(extentX),
                double(extentY));
  }
}
