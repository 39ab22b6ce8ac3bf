// Forward+ (a cluster_lights pass building the clustered light lists into a
// graph buffer, forward_lit and forward shading each fragment with its
// cluster's list): against the same pipelines with the `clusters` binding
// removed, so that the forward passes shade every light (same cut-off). The
// scenes have BLEND materials, and each test first checks that they show
// (the frame differs from the same scene with them opaque) and that the
// lights do (against the ambient-only frame), so that two black, unlit or
// opaque-only frames cannot agree.
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

json pipelineDoc(const std::string& file) {
  std::ifstream in(rtest::repoPath("pipelines/" + file));
  std::stringstream text;
  text << in.rdbuf();
  return json::parse(text.str());
}

json& passNamed(json& doc, const std::string& name) {
  for (json& pass : doc["passes"])
    if (pass["name"] == name) return pass;
  ADD_FAILURE() << "no pass " << name;
  static json none;
  return none;
}

// `file` as shipped, or with every forward pass's `clusters` binding removed
// (every light per fragment), or with `builder` params set on cluster_lights.
PipelineConfig pipeline(const std::string& file, bool clustered, const json& builder = json::object()) {
  json doc = pipelineDoc(file);
  for (json& pass : doc["passes"]) {
    if (pass["type"] == "cluster_lights") pass["params"].update(builder);
    if (!clustered && (pass["type"] == "forward_lit" || pass["type"] == "forward") && pass.contains("inputs"))
      pass["inputs"].erase("clusters");
  }
  return testsupport::buildPipelineOrThrow(doc.dump(), file + (clustered ? "" : " (every light)"));
}

rtest::Image renderAdapted(PipelineConfig cfg, const Scene& scene, Extent size, ShaderLibrary& shaders,
                           const std::function<void(Executor&)>& inspect = {}) {
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  return rtest::render(cfg, scene, size, shaders, inspect);
}

// The many-lights field with half its object materials see-through (BLEND, alpha 0.5).
Scene manyLightsWithGlass(int lights) {
  Scene s = makeManyLightsScene(lights);
  for (Material& m : s.materials)
    if (m.name == "object1" || m.name == "object3" || m.name == "object5") {
      m.alphaMode = AlphaMode::blend;
      m.baseColorFactor.a = 0.5f;
    }
  return s;
}

Scene opaque(Scene s) {
  for (Material& m : s.materials) m.alphaMode = AlphaMode::opaque;
  return s;
}

// The list buffer the pipeline's cluster_lights pass wrote: header, counts.
std::vector<uint32_t> clusterBuffer(const Executor& exec) {
  const GLuint buffer = exec.bufferOf("clusters");
  EXPECT_NE(buffer, 0u) << "no buffer 'clusters'";
  if (!buffer) return {};
  GLint64 bytes = 0;
  glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &bytes);
  std::vector<uint32_t> data(static_cast<size_t>(bytes) / 4);
  glGetNamedBufferSubData(buffer, 0, bytes, data.data());
  return data;
}

class ForwardPlus : public rtest::RenderTest {
 protected:
  // Renders `file` with and without its lists; expects the lights and the
  // blended surfaces to show and the two within 1/255.
  void expectMatchesEveryLight(const std::string& file, const Scene& scene, Extent size, double minLitShare,
                               double minBlendShare, const std::string& name, const json& builder = json::object(),
                               const std::function<void(Executor&)>& inspect = {}) {
    ShaderLibrary shaders;
    const PipelineConfig all = pipeline(file, false);
    const rtest::Image every = renderAdapted(all, scene, size, shaders);
    rtest::expectLightsShow(every, all, scene, shaders, minLitShare, name + "-every-light");
    const rtest::Image solid = renderAdapted(all, opaque(scene), size, shaders);
    const rtest::ImageDiff blend = rtest::compareImages(every, solid, 2);
    const double blendShare = double(blend.over) / (double(size.width) * size.height);
    std::printf("[ measure  ] %s: blended surfaces change %.1f%% of the pixels\n", name.c_str(), 100 * blendShare);
    EXPECT_GE(blendShare, minBlendShare) << "the blended surfaces do not show";

    const rtest::Image plus = renderAdapted(pipeline(file, true, builder), scene, size, shaders, inspect);
    const rtest::ImageDiff d = rtest::compareImages(plus, every, 1);
    std::printf("[ measure  ] %s: forward+ vs every light %s\n", name.c_str(), d.describe().c_str());
    EXPECT_EQ(d.over, 0u) << d.describe() << "; saved " << rtest::saveImage(plus, name + "-forward-plus") << ", "
                          << rtest::saveImage(every, name + "-every-light");
  }
};

TEST_F(ForwardPlus, ManyLightsWithBlendedObjectsMatchesForward) {
  // forward-plus.json (forward_lit with the lists, opaque and blended) against
  // forward_lit with every light: forward.json's passes.
  std::vector<uint32_t> data;
  expectMatchesEveryLight("forward-plus.json", manyLightsWithGlass(256), {160, 90}, 0.4, 0.05, "forward-plus-256",
                          json::object(), [&](Executor& exec) { data = clusterBuffer(exec); });
  // The lists cull: 160x90 at 32-pixel tiles and 24 slices is 5 x 3 x 24
  // clusters; ~16 of the 256 lights reach each point.
  constexpr size_t kClusters = 5 * 3 * 24;
  ASSERT_GE(data.size(), 4 + kClusters);
  EXPECT_EQ(data[0], 0u) << "overflowed clusters";
  EXPECT_EQ(data[1], 32u) << "tile size in the header";
  EXPECT_EQ(data[2], 24u) << "slices in the header";
  EXPECT_EQ(data[3], 128u) << "list length in the header";
  uint64_t sum = 0;
  for (size_t c = 0; c < kClusters; ++c) sum += data[4 + c];
  std::printf("[ measure  ] forward+ lists: mean %.1f lights per cluster\n", double(sum) / kClusters);
  EXPECT_GT(sum, 0u);
  EXPECT_LT(double(sum) / kClusters, 32.0);
}

TEST_F(ForwardPlus, AlphaBlendSceneMatchesForward) {
  // AlphaBlendModeTest (scenes/alpha-blend.json): BLEND quads over opaque ones, two point lights and a sun.
  const Scene scene = loadSceneAny(rtest::repoPath("scenes/alpha-blend.json"));
  expectMatchesEveryLight("forward-plus.json", scene, {160, 120}, 0.05, 0.02, "forward-plus-alpha-blend");
}

TEST_F(ForwardPlus, DeferredClusteredBlendPassMatchesEveryLight) {
  // deferred-clustered-forward-plus.json: one list build read by the
  // clustered lighting and by the forward pass over it (blended surfaces).
  ShaderLibrary shaders;
  const Scene scene = manyLightsWithGlass(256);
  PipelineConfig cfg = pipeline("deferred-clustered-forward-plus.json", true);
  adaptToScene(cfg, processRegistry(), sceneFeatures(scene));
  Executor exec(cfg, processRegistry(), shaders, &scene);
  exec.resize({64, 36});
  const Plan& plan = exec.plan();
  size_t builders = 0;
  std::vector<std::string> readers;
  for (const PlannedPass& p : plan.passes) {
    if (p.culled) continue;
    builders += p.type == "cluster_lights";
    for (const BoundUse& u : plan.uses(p.decl))
      if (u.slot == "clusters" && u.access == Access::storage_read) readers.push_back(p.name);
  }
  EXPECT_EQ(builders, 1u) << "the lists are built once a frame";
  EXPECT_EQ(readers, (std::vector<std::string>{"clustered_lighting", "forward_plus"}));

  expectMatchesEveryLight("deferred-clustered-forward-plus.json", scene, {160, 90}, 0.4, 0.05,
                          "deferred-clustered-forward-plus-256");
}

TEST_F(ForwardPlus, OverflowingClusterListsShadeEveryLight) {
  // Lists of 4 where ~16 lights reach each point: the overflowing clusters
  // are counted and their fragments shade every light, so the image still
  // matches.
  std::vector<uint32_t> data;
  expectMatchesEveryLight("forward-plus.json", manyLightsWithGlass(256), {128, 72}, 0.4, 0.05,
                          "forward-plus-cluster-overflow", {{"max_cluster_lights", 4}},
                          [&](Executor& exec) { data = clusterBuffer(exec); });
  ASSERT_FALSE(data.empty());
  std::printf("[ measure  ] %u clusters overflowed lists of 4\n", data[0]);
  EXPECT_GT(data[0], 10u);
  EXPECT_EQ(data[3], 4u);
}

TEST_F(ForwardPlus, ClusterLightStraddlingTheNearPlaneLightsAsEveryLight) {
  // A bright light between the eye and the near plane, in front of blended
  // surfaces: its sphere holds the eye and cuts the near plane, its centre
  // outside every cluster's depth range; the nearest clusters must list it.
  Scene scene = manyLightsWithGlass(64);
  PointLight light;
  light.position = scene.camera.position + scene.camera.forward() * (scene.camera.near * 0.5f);
  light.color = glm::vec3(1.0f, 0.9f, 0.6f);
  light.intensity = 3.0f;
  light.linear = 0.02f;
  light.quadratic = 0.002f;
  light.radius = lightRadius(light);
  scene.pointLights.push_back(light);
  expectMatchesEveryLight("forward-plus.json", scene, {128, 72}, 0.4, 0.05, "forward-plus-near-plane");

  Scene without = scene;
  without.pointLights.pop_back();
  ShaderLibrary shaders;
  const rtest::Image with = renderAdapted(pipeline("forward-plus.json", true), scene, {128, 72}, shaders);
  const rtest::Image before = renderAdapted(pipeline("forward-plus.json", true), without, {128, 72}, shaders);
  const rtest::LightGain gain = rtest::lightGain(with, before, rtest::kMinLightGain);
  std::printf("[ measure  ] the near-plane light brightens %s\n", gain.describe().c_str());
  EXPECT_GE(gain.share(), 0.2) << "the light around the camera does not reach the forward+ frame";
}

}  // namespace
