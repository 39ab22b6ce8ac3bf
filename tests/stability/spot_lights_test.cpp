// Spot lights (issue 14) lit by every lighting method against the fullscreen
// deferred_lighting loop, which shades every light at every pixel through
// include/lighting.glsl's spotCone (itself checked against the glTF formula by
// tests/oracle). The methods differ only in which pixels each light is
// evaluated at: light volumes draw a cone mesh per spot light, tiled and
// clustered shading cull each cone against tiles and clusters, forward_lit
// shades every light per fragment. With the same fp32 G-buffer and rgba32f
// HDR target, every deferred method must match the loop within 1/255 on the
// linear 8-bit output, and so must forward_lit (its own rasterised positions;
// measured: all of them equal, 0/255).
//
// The scene: a floor, a cube and a sphere, five spot lights (narrow, medium,
// wide past 45 degrees, a 90-degree half-space, one tilted so its cone ends
// in mid-air at its cut-off) and one point light; their cone edges cross many
// 16- and 32-pixel tiles. Guards: the reference shows its lights (against its
// ambient-only frame), and the cones matter (the same lights without cones
// light many more pixels), so two unlit or two cone-less frames cannot agree.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <GL/glcorearb.h>

#include "rgraph/pipeline_load.h"
#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;
using nlohmann::json;

namespace {

constexpr Extent kSize{144, 96};
constexpr double kThreshold = 5.0 / 256.0;

PointLight spot(glm::vec3 pos, glm::vec3 dir, float innerDeg, float outerDeg, glm::vec3 color, float intensity,
                float linear, float quadratic) {
  PointLight l = pointLight(pos, color, intensity, 1.0f, linear, quadratic);
  l.spot = true;
  l.direction = glm::normalize(dir);
  l.innerConeDeg = innerDeg;
  l.outerConeDeg = outerDeg;
  l.radius = lightRadius(l);
  return l;
}

Scene spotScene() {
  Scene s;
  s.source = "test:spots";
  const int plane = addMesh(s, makePlane(8.0f, 8.0f));
  const int cube = addMesh(s, makeCube(0.6f));
  const int sphere = addMesh(s, makeUvSphere(0.7f));
  addDraw(s, plane, addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.7f, 0.3f), glm::mat4(1.0f), "floor");
  addDraw(s, cube, addMaterial(s, {0.7f, 0.3f, 0.2f, 1.0f}, 0.0f, 0.5f, 0.6f),
          glm::rotate(translate({-1.5f, 0.6f, 0.5f}), 0.6f, glm::vec3(0, 1, 0)), "cube");
  addDraw(s, sphere, addMaterial(s, {0.2f, 0.5f, 0.8f, 1.0f}, 0.3f, 0.3f, 0.8f), translate({1.6f, 0.7f, -0.8f}),
          "sphere");
  s.pointLights = {
      spot({0.0f, 3.0f, 0.5f}, {0.1f, -1.0f, 0.0f}, 8.0f, 22.0f, {1.0f, 0.9f, 0.7f}, 4.0f, 0.35f, 0.44f),
      spot({-3.5f, 2.0f, 2.0f}, {1.0f, -0.8f, -0.3f}, 30.0f, 60.0f, {0.5f, 0.8f, 1.0f}, 3.0f, 0.35f, 0.44f),
      spot({3.0f, 1.2f, 2.5f}, {-0.6f, -0.5f, -1.0f}, 4.0f, 10.0f, {1.0f, 0.4f, 0.3f}, 6.0f, 0.35f, 0.44f),
      spot({2.5f, 1.5f, -3.0f}, {0.0f, -1.0f, 0.0f}, 70.0f, 90.0f, {0.6f, 1.0f, 0.5f}, 1.6f, 0.7f, 1.8f),
      // Tilted up: its cone ends in mid-air at its cut-off, beyond the sphere.
      spot({-0.5f, 0.4f, -1.5f}, {0.9f, 0.25f, -0.2f}, 15.0f, 35.0f, {1.0f, 0.8f, 1.0f}, 2.0f, 0.7f, 1.8f),
      pointLight({-2.0f, 0.8f, -2.5f}, {0.9f, 0.7f, 0.4f}, 1.0f),
  };
  s.ambient = glm::vec3(0.03f);
  placeCamera(s, glm::vec3(0.5f, 5.5f, 8.0f), glm::vec3(0.0f, 0.0f, -0.5f), 50.0f, 0.1f, 40.0f);
  return s;
}


struct Method {
  std::string name;
  json doc;
  int tolerance;  // 8-bit, max over pixels and channels
};

std::vector<Method> methods(const LightingParams& l) {
  return {{"light_volumes", lightVolumesPipeline("front", l), 1},
          {"tiled_deferred", computePipeline("tiled_deferred", l), 1},
          {"clustered_deferred", computePipeline("clustered_deferred", l), 1},
          {"forward_lit", forwardPipeline(l), 1}};
}

void expectEveryMethodMatchesFullscreen(const Scene& scene, const LightingParams& l, const std::string& name) {
  const size_t pixels = size_t{kSize.width} * kSize.height;
  const Frame ref = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "fullscreen"), scene, kSize);
  Scene dark = scene, coneless = scene;
  dark.pointLights.clear();
  for (PointLight& p : coneless.pointLights) p.spot = false;
  const Frame ambient = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "ambient"), dark, kSize);
  const Frame points = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "points"), coneless, kSize);
  const size_t lit = pixelsBrighter(ref, ambient, 8), cut = pixelsBrighter(points, ref, 8);
  std::printf("[ measure  ] %s: the lights brighten %.1f%% of the pixels; without cones %.1f%% more are lit\n",
              name.c_str(), 100.0 * lit / pixels, 100.0 * cut / pixels);
  ASSERT_GE(lit, pixels / 4) << "the reference does not show its lights";
  ASSERT_GE(cut, pixels / 5) << "the cones should cut away much of the light";
  for (const Method& m : methods(l)) {
    const Frame f = renderFrame(pipelineFromJson(m.doc, m.name), scene, kSize);
    const Diff d = compare8(f.rgba, ref.rgba, kSize);
    std::printf("[ measure  ] %s: %s vs fullscreen: %s\n", name.c_str(), m.name.c_str(), d.describe().c_str());
    EXPECT_LE(d.maxAbs, m.tolerance) << m.name << ": " << d.describe() << "; saved "
                                     << saveImage(f.rgba, kSize, name + "-" + m.name) << " and "
                                     << saveImage(ref.rgba, kSize, name + "-fullscreen");
  }
}

}  // namespace

TEST_F(Stability, SpotLightsEveryMethodMatchesFullscreenBlinnPhong) {
  expectEveryMethodMatchesFullscreen(spotScene(), {"blinn_phong", "classic", kThreshold}, "spots-bp");
}

TEST_F(Stability, SpotLightsEveryMethodMatchesFullscreenPbr) {
  expectEveryMethodMatchesFullscreen(spotScene(), {"cook_torrance", "smooth", kThreshold}, "spots-pbr");
}

TEST_F(Stability, SpotLightsWithoutCutOffMatchFullscreen) {
  // Threshold 0: no cut-off (light volumes need one and are left out); the
  // cones alone decide what tiles and clusters list.
  const LightingParams l{"blinn_phong", "classic", 0.0};
  const Scene scene = spotScene();
  const Frame ref = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "fullscreen"), scene, kSize);
  for (const char* type : {"tiled_deferred", "clustered_deferred"}) {
    const Frame f = renderFrame(pipelineFromJson(computePipeline(type, l), type), scene, kSize);
    const Diff d = compare8(f.rgba, ref.rgba, kSize);
    std::printf("[ measure  ] no cut-off: %s vs fullscreen: %s\n", type, d.describe().c_str());
    EXPECT_LE(d.maxAbs, 1) << type << ": " << d.describe();
  }
}

// Where culling too tightly would show: a spot light aimed at a wall with a
// high cut-off threshold (0.15), so that its cut-off is a sharp step of ~25/255
// on the wall. (a) a 40-degree cone whose sphere meets the wall well inside the
// cone (the bounding sphere of narrow cones); (b) a 65-degree cone with the
// wall near r cos(outer), where the step runs close to the cone's rim (the
// bounding sphere of wide cones); (c) a hard-edged cone (inner 29.5, outer 30)
// reaching far past the wall, whose rim is a sharp step (the cone tests). Every
// method must match the fullscreen loop within 1/255.
TEST_F(Stability, SpotLightCutOffAndHardEdgesMatchFullscreen) {
  struct Case {
    const char* name;
    float inner, outer, wallDistance, intensity, cameraDistance;  // the camera's distance from the wall
  };
  constexpr double kHighThreshold = 0.15;
  for (const Case& c : {Case{"narrow-cut", 20.0f, 40.0f, 3.0f, 3.4f, 3.7f}, Case{"wide-cut", 40.0f, 65.0f, 1.5f, 3.4f, 8.0f},
                        Case{"hard-edge", 29.5f, 30.0f, 2.0f, 20.0f, 3.2f}}) {
    SCOPED_TRACE(c.name);
    Scene s;
    s.source = "test:spot-wall";
    const int cube = addMesh(s, makeCube(1.0f));
    addDraw(s, cube, addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.6f, 0.2f),
            glm::scale(translate({0.0f, 0.0f, -0.25f}), glm::vec3(6.0f, 6.0f, 0.25f)), "wall");
    s.pointLights.push_back(spot({0.2f, -0.1f, c.wallDistance}, {0.1f, 0.05f, -1.0f}, c.inner, c.outer,
                                 {1.0f, 0.9f, 0.8f}, c.intensity, 0.7f, 1.8f));
    s.ambient = glm::vec3(0.02f);
    placeCamera(s, glm::vec3(0.0f, 0.0f, c.cameraDistance), glm::vec3(0.0f), 60.0f, 0.1f, 30.0f);
    const LightingParams l{"blinn_phong", "classic", kHighThreshold};
    const float r = lightRadius(s.pointLights[0], float(kHighThreshold));
    if (std::string(c.name) != "hard-edge") ASSERT_LT(c.wallDistance, r) << "the cut-off must reach the wall";
    const Frame ref = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "fullscreen"), s, kSize);
    Scene dark = s;
    dark.pointLights.clear();
    const Frame ambient = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, l), "ambient"), dark, kSize);
    const size_t pixels = size_t{kSize.width} * kSize.height, lit = pixelsBrighter(ref, ambient, 8);
    std::printf("[ measure  ] %s (radius %.2f): lit on %.1f%% of the pixels\n", c.name, r, 100.0 * lit / pixels);
    ASSERT_GE(lit, pixels / 20);
    ASSERT_LE(lit, pixels * 9 / 10) << "the step must be in view";
    for (const Method& m : methods(l)) {
      const Frame f = renderFrame(pipelineFromJson(m.doc, m.name), s, kSize);
      const Diff d = compare8(f.rgba, ref.rgba, kSize);
      std::printf("[ measure  ] %s: %s vs fullscreen: %s\n", c.name, m.name.c_str(), d.describe().c_str());
      EXPECT_LE(d.maxAbs, m.tolerance) << m.name << ": " << d.describe() << "; saved "
                                       << saveImage(f.rgba, kSize, std::string(c.name) + "-" + m.name) << " and "
                                       << saveImage(ref.rgba, kSize, std::string(c.name) + "-fullscreen");
    }
  }
}

// The camera inside a spot light's cone volume: the light 1 unit behind the
// camera, pointing past it at a wall. Light volumes draw the cone's far side
// (front faces culled, depth clamped), which lies beyond the camera, so the
// light is kept; culling back faces draws the near side, behind the camera,
// and loses it (kept to show why the default is front).
TEST_F(Stability, CameraInsideSpotLightVolume) {
  Scene s;
  s.source = "test:spot-wall";
  const int cube = addMesh(s, makeCube(1.0f));
  addDraw(s, cube, addMaterial(s, {0.8f, 0.8f, 0.8f, 1.0f}, 0.0f, 0.6f, 0.5f),
          glm::scale(translate({0.0f, 0.0f, -0.25f}), glm::vec3(4.0f, 4.0f, 0.25f)), "wall");
  s.pointLights.push_back(
      spot({0.0f, 0.0f, 3.0f}, {0.05f, 0.0f, -1.0f}, 15.0f, 30.0f, {1.0f, 0.9f, 0.7f}, 1.0f, 0.09f, 0.032f));
  s.ambient = glm::vec3(0.05f);
  placeCamera(s, glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(0.0f), 60.0f, 0.05f, 20.0f);
  const PointLight& l = s.pointLights[0];
  const glm::vec3 toCamera = s.camera.position - l.position;
  ASSERT_LT(glm::length(toCamera), lightRadius(l, float(kThreshold)));
  ASSERT_LT(std::acos(glm::dot(glm::normalize(toCamera), l.direction)), glm::radians(l.outerConeDeg))
      << "the camera must be inside the cone";

  const LightingParams lp{"blinn_phong", "classic", kThreshold};
  Scene dark = s;
  dark.pointLights.clear();
  const Frame ref = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, lp), "fullscreen"), s, kSize);
  const Frame ambient = renderFrame(pipelineFromJson(fullscreenPipeline({"fp32", ""}, lp), "ambient"), dark, kSize);
  const Frame front = renderFrame(pipelineFromJson(lightVolumesPipeline("front", lp), "front"), s, kSize);
  const Frame back = renderFrame(pipelineFromJson(lightVolumesPipeline("back", lp), "back"), s, kSize);
  const size_t pixels = size_t{kSize.width} * kSize.height, lit = pixelsBrighter(ref, ambient, 8);
  const Diff df = compare8(front.rgba, ref.rgba, kSize), db = compare8(back.rgba, ref.rgba, kSize);
  std::printf("[ measure  ] camera inside a spot cone: light on %.1f%% of the pixels; cull front %s; cull back %s\n",
              100.0 * lit / pixels, df.describe().c_str(), db.describe().c_str());
  ASSERT_GE(lit, pixels / 5);
  EXPECT_LE(df.maxAbs, 1) << df.describe() << "; saved " << saveImage(front.rgba, kSize, "spot-inside-front");
  EXPECT_GE(db.maxAbs, 32) << "culling back faces was expected to lose the light around the camera";
  EXPECT_LE(pixelsBrighter(back, ambient, 8), pixels / 100);
}

// Culling: a narrow spot light is listed in far fewer clusters than the same
// light without its cone, and a wide one (past 45 degrees, whose bounding
// sphere is nearly its whole cut-off sphere) in fewer too, by the cone test.
TEST_F(Stability, ClustersListSpotLightsOnlyWhereTheirConesReach) {
  auto listed = [](const PointLight& light) {
    Scene s = spotScene();
    s.pointLights = {light};
    // The lists a cluster_lights pass builds: every cluster's, whether it
    // holds pixels or not (clustered_deferred's own lists only those with
    // pixels, bounded by their depths). 144x96 at its default 32-pixel tiles,
    // 24 slices and 256 lights a list: (4 + 5 x 3 x 24 x 257) x 4 bytes.
    json doc = computePipeline("clustered_deferred", {"blinn_phong", "classic", kThreshold});
    doc["resources"]["clusters"] = {{"type", "buffer"}, {"buffer_bytes", 370096}};
    doc["passes"].insert(doc["passes"].begin(), json{{"name", "cluster_lights"},
                                                     {"type", "cluster_lights"},
                                                     {"params", {{"threshold", kThreshold}}},
                                                     {"outputs", {{"clusters", "clusters"}}}});
    for (json& pass : doc["passes"])
      if (pass["name"] == "lighting") pass["inputs"]["clusters"] = "clusters";
    const PipelineConfig cfg = pipelineFromJson(doc, "clustered");
    Executor exec(cfg, processRegistry(), sharedShaders(), &s);
    exec.resize(kSize);
    exec.renderFrame();
    GLint buffer = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &buffer);
    EXPECT_NE(buffer, 0);
    GLint64 bytes = 0;
    glGetNamedBufferParameteri64v(GLuint(buffer), GL_BUFFER_SIZE, &bytes);
    std::vector<uint32_t> data(size_t(bytes) / 4);
    glGetNamedBufferSubData(GLuint(buffer), 0, bytes, data.data());
    // 144x96 at 32-pixel tiles and 24 slices: 5 x 3 x 24 clusters after the 4-uint header.
    constexpr size_t kClusters = 5 * 3 * 24;
    EXPECT_GE(data.size(), 4 + kClusters);
    uint32_t n = 0;
    for (size_t c = 0; c < kClusters && 4 + c < data.size(); ++c) n += data[4 + c];
    return n;
  };
  for (const auto& [name, l] :
       {std::pair<std::string, PointLight>{"narrow", spotScene().pointLights[0]}, {"wide", spotScene().pointLights[1]}}) {
    PointLight point = l;
    point.spot = false;
    const uint32_t cone = listed(l), sphere = listed(point);
    std::printf("[ measure  ] %s spot light (outer %.0f degrees): listed in %u clusters, %u without its cone\n",
                name.c_str(), l.outerConeDeg, cone, sphere);
    EXPECT_GT(cone, 0u);
    EXPECT_LT(cone * 10, sphere * (name == "narrow" ? 2u : 5u)) << name;
  }
}
