// Dropping the material target must not change the picture.
#include <gtest/gtest.h>

#include <cstdlib>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/cube_scene.h"

namespace rgraph {
namespace {

std::vector<uint8_t> render(const PipelineConfig& pipeline, const Scene& scene, Extent size) {
  ShaderLibrary shaders;
  Executor exec(pipeline, processRegistry(), shaders, &scene);
  exec.resize(size);
  exec.renderFrame();
  return exec.readOutputRGBA8();
}

TEST(AdaptRender, ConstantMaterialRendersLikeTheMaterialTarget) {
  auto context = GlContext::create();
  Diagnostics diags;
  PipelineConfig full =
      ConfigDocument::parseFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr.json", diags)
          .build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags));
  // Suzanne-free, texture-free: a sphere with one metallic/roughness, lit by a point light.
  Material m;
  m.baseColorFactor = {0.8f, 0.3f, 0.2f, 1.0f};
  m.metallicFactor = 0.6f;
  m.roughnessFactor = 0.35f;
  Scene scene = testsupport::singleMeshScene(makeUvSphere(1.0f, 24, 12), m);
  PointLight l;
  l.position = {1.5f, 1.5f, 2.0f};
  l.color = {1.0f, 0.9f, 0.8f};
  l.intensity = 4.0f;
  scene.pointLights.push_back(l);
  scene.camera.position = {0, 0, 4};
  scene.hasCamera = true;

  PipelineConfig adapted = full;
  const AdaptReport report = adaptToScene(adapted, processRegistry(), sceneFeatures(scene));
  ASSERT_FALSE(report.notes.empty());
  const Extent size{96, 96};
  const auto a = render(full, scene, size);
  const auto b = render(adapted, scene, size);
  ASSERT_EQ(a.size(), b.size());
  int maxDiff = 0, lit = 0;
  for (size_t i = 0; i < a.size(); ++i) maxDiff = std::max(maxDiff, std::abs(int(a[i]) - int(b[i])));
  for (size_t i = 0; i < a.size(); i += 4) lit += a[i] > 40;
  EXPECT_GT(lit, 500);  // the sphere is there and lit
  // The material target is rgba16f: 0.6 and 0.35 are stored to ~1e-3, the
  // constant is exact. Within 1/255 everywhere.
  EXPECT_LE(maxDiff, 1);
  EXPECT_EQ(context->debugErrorCount(), 0u) << context->lastDebugError();
}

}  // namespace
}  // namespace rgraph
