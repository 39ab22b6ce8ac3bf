// clustered_deferred (pipelines/deferred-clustered.json) against the
// fullscreen deferred_lighting pass: the same pipeline with the clustered
// pass swapped for deferred_lighting (same G-buffer, lighting parameters and
// cut-off threshold) must give the same image within 1/255, on the
// many-lights scene, the LearnOpenGL scene, with a light whose sphere holds
// the camera and crosses the near plane, and with clusters that hold fewer
// lights than reach them (overflow: counted, and every light shaded).
// Each comparison first checks that the reference shows its lights against
// its ambient-only frame, so two black or two unlit frames cannot agree.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rgraph/adapt.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"
#include "support/test_support.h"

namespace {
using namespace rgraph;
using nlohmann::json;

// pipelines/deferred-clustered.json, its lighting pass given `params`, or
// turned into the fullscreen deferred_lighting pass (`fullscreen`).
PipelineConfig clusteredPipeline(bool fullscreen, const json& params = json::object()) {
  std::ifstream in(rtest::repoPath("pipelines/deferred-clustered.json"));
  std::stringstream text;
  text << in.rdbuf();
  json doc = json::parse(text.str());
  bool found = false;
  for (json& pass : doc["passes"]) {
    if (pass["type"] != "clustered_deferred") continue;
    found = true;
    if (fullscreen) {
      pass["type"] = "deferred_lighting";
      for (const char* key : {"tile_size", "slices", "max_cluster_lights"}) pass["params"].erase(key);
    } else {
      pass["params"].update(params);
    }
  }
  EXPECT_TRUE(found) << "deferred-clustered.json has no clustered_deferred pass";
  return testsupport::buildPipelineOrThrow(doc.dump(), fullscreen ? "<fullscreen reference>" : "<clustered>");
}

rtest::Image renderAdapted(PipelineConfig cfg, const Scene& scene, Extent size, ShaderLibrary& shaders,
                           const std::function<void(Executor&)>& inspect = {}) {
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  return rtest::render(cfg, scene, size, shaders, inspect);
}

// The cluster buffer's header: clusters whose lights passed
// max_cluster_lights this frame. The pass leaves the buffer on storage
// binding 1 (no later pass of the pipeline binds one there).
// The whole buffer: a 4-uint header, then one light count per cluster.
std::vector<uint32_t> clusterBuffer() {
  GLint buffer = 0;
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &buffer);
  EXPECT_NE(buffer, 0) << "no buffer on storage binding 1 after the frame";
  if (!buffer) return {};
  GLint64 bytes = 0;
  glGetNamedBufferParameteri64v(static_cast<GLuint>(buffer), GL_BUFFER_SIZE, &bytes);
  std::vector<uint32_t> data(static_cast<size_t>(bytes) / 4);
  glGetNamedBufferSubData(static_cast<GLuint>(buffer), 0, bytes, data.data());
  return data;
}
uint32_t overflowedClusters() {
  const std::vector<uint32_t> data = clusterBuffer();
  return data.empty() ? 0 : data[0];
}

class Clustered : public rtest::RenderTest {
 protected:
  // Renders the clustered and fullscreen pipelines; expects the reference's
  // lights to show on `minLitShare` of the pixels and the two within 1/255.
  void expectMatchesFullscreen(const Scene& scene, Extent size, double minLitShare, const std::string& name,
                               const json& params = json::object(), uint32_t* overflowed = nullptr) {
    ShaderLibrary shaders;
    const PipelineConfig ref = clusteredPipeline(true);
    const rtest::Image full = renderAdapted(ref, scene, size, shaders);
    rtest::expectLightsShow(full, ref, scene, shaders, minLitShare, name + "-fullscreen");
    const rtest::Image clustered =
        renderAdapted(clusteredPipeline(false, params), scene, size, shaders, [&](Executor&) {
          if (overflowed) *overflowed = overflowedClusters();
        });
    const rtest::ImageDiff d = rtest::compareImages(clustered, full, 1);
    std::printf("[ measure  ] %s: clustered vs fullscreen %s\n", name.c_str(), d.describe().c_str());
    EXPECT_EQ(d.over, 0u) << d.describe() << "; saved " << rtest::saveImage(clustered, name + "-clustered") << ", "
                          << rtest::saveImage(full, name + "-fullscreen");
  }
};

TEST_F(Clustered, ManyLightsMatchesFullscreen) {
  uint32_t overflowed = 99;
  expectMatchesFullscreen(makeManyLightsScene(256), {160, 90}, 0.4, "clustered-many-lights-256", json::object(),
                          &overflowed);
  EXPECT_EQ(overflowed, 0u) << "~16 lights reach each point: no cluster should pass 256";
}

TEST_F(Clustered, PillarsSceneMatchesFullscreen) {
  // many-lights:N:pillars: thin pillars close to the camera over the field
  // and a far wall, so tiles hold pixels at both ends of the depth range and
  // slices near the camera are a fraction of a pillar deep.
  uint32_t overflowed = 99;
  expectMatchesFullscreen(makeManyLightsPillarsScene(256), {160, 90}, 0.3, "clustered-pillars-256", json::object(),
                          &overflowed);
  EXPECT_EQ(overflowed, 0u);
}

TEST_F(Clustered, ListsHoldOnlyNearbyLights) {
  // Culling works: 160x90 at 32-pixel tiles and 24 slices is 5 x 3 x 24
  // clusters; with ~16 of the 256 lights reaching each point, the lists
  // must be far shorter than every light (a cull that keeps everything
  // would still match fullscreen).
  const Scene scene = makeManyLightsScene(256);
  ShaderLibrary shaders;
  std::vector<uint32_t> data;
  renderAdapted(clusteredPipeline(false), scene, {160, 90}, shaders, [&](Executor&) { data = clusterBuffer(); });
  constexpr size_t kClusters = 5 * 3 * 24;
  ASSERT_EQ(data.size(), 4 + kClusters * (1 + 256));
  uint64_t sum = 0;
  uint32_t most = 0;
  size_t empty = 0;
  for (size_t c = 0; c < kClusters; ++c) {
    sum += data[4 + c];
    most = std::max(most, data[4 + c]);
    empty += data[4 + c] == 0;
  }
  const double mean = double(sum) / kClusters;
  std::printf("[ measure  ] lights per cluster: mean %.1f, most %u, %zu of %zu clusters empty\n", mean, most, empty,
              kClusters);
  EXPECT_LT(mean, 32.0);
  EXPECT_LT(most, 128u);
  EXPECT_GT(sum, 0u);
}

TEST_F(Clustered, LearnOpenGLMatchesFullscreen) {
  // The camera at (0,0,5) sits inside several of the 32 lights' volumes;
  // partial tiles at the right and top edges (150 x 100, 32-pixel tiles).
  expectMatchesFullscreen(makeLearnOpenGLScene(), {150, 100}, 0.1, "clustered-learnopengl");
}

TEST_F(Clustered, ZeroPointLightsGivesAmbientAndSun) {
  // No point lights: the list build is skipped; the sun and ambient remain.
  Scene scene = makeManyLightsScene(0);
  scene.directionalLights.push_back(
      DirectionalLight{glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f)), glm::vec3(1.0f), 1.0f});
  expectMatchesFullscreen(scene, {96, 64}, 0.4, "clustered-zero-lights");
}

TEST_F(Clustered, LightStraddlingTheNearPlaneLightsAsFullscreen) {
  // A bright light between the eye and the near plane: its sphere holds the
  // eye and cuts the near plane, its centre outside every cluster's depth
  // range. The lit-share guard compares against ambient only; the check
  // after it against the same scene without this light.
  Scene scene = makeLearnOpenGLScene();
  PointLight light;
  light.position = scene.camera.position + scene.camera.forward() * (scene.camera.near * 0.5f);
  light.color = glm::vec3(1.0f, 0.9f, 0.6f);
  light.intensity = 3.0f;
  light.linear = 0.09f;
  light.quadratic = 0.032f;
  light.radius = lightRadius(light);
  scene.pointLights.push_back(light);
  expectMatchesFullscreen(scene, {128, 96}, 0.2, "clustered-near-plane");  // measured 32.1%

  Scene without = scene;
  without.pointLights.pop_back();
  ShaderLibrary shaders;
  const rtest::Image with = renderAdapted(clusteredPipeline(false), scene, {128, 96}, shaders);
  const rtest::Image before = renderAdapted(clusteredPipeline(false), without, {128, 96}, shaders);
  const rtest::LightGain gain = rtest::lightGain(with, before, rtest::kMinLightGain);
  std::printf("[ measure  ] the near-plane light brightens %s\n", gain.describe().c_str());
  EXPECT_GE(gain.share(), 0.2) << "the light around the camera does not reach the clustered frame";
}

TEST_F(Clustered, MoreTileCandidatesThanSharedMemoryHoldsTestsEveryLight) {
  // No cut-off: all 1,100 lights reach every tile, past the 1,024 candidates
  // a tile keeps in shared memory (clustered_build.comp), so the build tests
  // every light per slice; lists of 2,048 hold them all (no overflow). (The
  // bins the build culls first overflow too: past 512 lights a tile culls
  // every light.)
  const Scene scene = makeManyLightsScene(1100);
  const json params = {{"threshold", 0.0}, {"max_cluster_lights", 2048}};
  ShaderLibrary shaders;
  std::vector<uint32_t> data;
  PipelineConfig ref = clusteredPipeline(true);
  rtest::setParam(ref, "clustered_lighting", "threshold", 0.0);
  const rtest::Image full = renderAdapted(ref, scene, {64, 36}, shaders);
  rtest::expectLightsShow(full, ref, scene, shaders, 0.4, "clustered-candidates-fullscreen");
  const rtest::Image clustered = renderAdapted(clusteredPipeline(false, params), scene, {64, 36}, shaders,
                                               [&](Executor&) { data = clusterBuffer(); });
  constexpr size_t kClusters = 2 * 2 * 24;
  ASSERT_EQ(data.size(), 4 + kClusters * (1 + 2048));
  EXPECT_EQ(data[0], 0u) << "overflowed clusters";
  // clustered_deferred lists lights only for clusters that hold pixels (their
  // pixels' depths bound them): every such cluster lists all 1,100.
  size_t withPixels = 0;
  for (size_t c = 0; c < kClusters; ++c)
    if (data[4 + c] != 0u) {
      ASSERT_EQ(data[4 + c], 1100u) << "cluster " << c;
      ++withPixels;
    }
  EXPECT_GE(withPixels, 4u) << "every tile has clusters with pixels";
  const rtest::ImageDiff d = rtest::compareImages(clustered, full, 1);
  std::printf("[ measure  ] no cut-off, 1,100 lights: clustered vs fullscreen %s\n", d.describe().c_str());
  EXPECT_EQ(d.over, 0u) << d.describe();
}

TEST_F(Clustered, ResizeRebuildsTheClusterGrid) {
  // Small, then larger: the list buffer must grow with the grid (200x120 at
  // 32-pixel tiles: 7 x 4 x 24 clusters) and the frame still match.
  const Scene scene = makeManyLightsScene(64);
  ShaderLibrary shaders;
  PipelineConfig cfg = clusteredPipeline(false);
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  Executor exec(cfg, processRegistry(), shaders, &scene);
  exec.resize({64, 48});
  exec.renderFrame();
  exec.resize({200, 120});
  exec.renderFrame();
  EXPECT_EQ(clusterBuffer().size(), 4 + size_t{7 * 4 * 24} * (1 + 256));
  rtest::Image resized;
  resized.extent = exec.outputExtent();
  resized.rgba = exec.readOutputRGBA8();
  const rtest::Image full = renderAdapted(clusteredPipeline(true), scene, {200, 120}, shaders);
  rtest::expectLightsShow(full, clusteredPipeline(true), scene, shaders, 0.4, "clustered-resize-fullscreen");
  const rtest::ImageDiff d = rtest::compareImages(resized, full, 1);
  EXPECT_EQ(d.over, 0u) << d.describe();
}

TEST_F(Clustered, OverflowingClustersAreCountedAndShadeEveryLight) {
  // ~16 volumes overlap each point of the many-lights scene: lists of 4 overflow.
  const Scene scene = makeManyLightsScene(256);
  const Extent size{128, 72};
  uint32_t overflowed = 0;
  expectMatchesFullscreen(scene, size, 0.4, "clustered-overflow", {{"max_cluster_lights", 4}}, &overflowed);
  std::printf("[ measure  ] %u clusters overflowed lists of 4\n", overflowed);
  EXPECT_GT(overflowed, 10u);

  // Truncated lists (overflow "truncate") lose the lights past the 4th: the
  // fallback above is what keeps the image right.
  ShaderLibrary shaders;
  const rtest::Image full = renderAdapted(clusteredPipeline(true), scene, size, shaders);
  const rtest::Image cut = renderAdapted(
      clusteredPipeline(false, {{"max_cluster_lights", 4}, {"overflow", "truncate"}}), scene, size, shaders);
  const rtest::ImageDiff d = rtest::compareImages(cut, full, rtest::kMinLightGain);
  std::printf("[ measure  ] truncated lists vs fullscreen: %s\n", d.describe().c_str());
  EXPECT_GT(d.over, size.width * size.height / 10u) << "truncating overflowing lists should lose light";
}

}  // namespace
