// "Model no more than a scene needs": each case builds a scene lacking one
// feature, adapts a shipped pipeline to it and checks the compiled plan.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/cube_scene.h"

namespace rgraph {
namespace {

PipelineConfig loadShipped(const std::string& name) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + name, diags);
  PipelineConfig p = doc.build(processRegistry(), diags);
  EXPECT_FALSE(hasErrors(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  return p;
}

const PlannedPass& passNamed(const Plan& plan, const std::string& name) {
  auto it = std::find_if(plan.passes.begin(), plan.passes.end(), [&](const PlannedPass& p) { return p.name == name; });
  EXPECT_NE(it, plan.passes.end()) << name;
  return *it;
}

const PlannedResource& resourceNamed(const Plan& plan, const std::string& name) {
  auto it = std::find_if(plan.resources.begin(), plan.resources.end(),
                         [&](const PlannedResource& r) { return r.name == name; });
  EXPECT_NE(it, plan.resources.end()) << name;
  return *it;
}

// A scene with one opaque cube, one material and nothing else.
Scene cubeScene() {
  Material m;
  m.metallicFactor = 0.25f;
  m.roughnessFactor = 0.75f;
  Scene s = testsupport::singleMeshScene(makeCube(0.5f), m);
  s.directionalLights.push_back(DirectionalLight{});
  return s;
}

struct Adapted {
  PipelineConfig before, after;
  Plan planBefore, planAfter;
  AdaptReport report;
};

Adapted adapt(const std::string& pipeline, const Scene& scene) {
  Adapted a;
  a.before = loadShipped(pipeline);
  a.after = a.before;
  a.report = adaptToScene(a.after, processRegistry(), sceneFeatures(scene));
  a.planBefore = compile(a.before.graph, CompileOptions{Extent{640, 360}});
  a.planAfter = compile(a.after.graph, CompileOptions{Extent{640, 360}});
  EXPECT_TRUE(a.planBefore.ok());
  EXPECT_TRUE(a.planAfter.ok()) << (a.planAfter.diagnostics.empty() ? "" : a.planAfter.diagnostics[0].message);
  return a;
}

TEST(AdaptToScene, NoPointLightsDropsTheLightVolumePass) {
  Scene scene = cubeScene();
  ASSERT_FALSE(scene.hasPointLights());
  Adapted a = adapt("deferred-light-volumes.json", scene);
  EXPECT_FALSE(passNamed(a.planBefore, "light_volumes").culled);
  EXPECT_TRUE(passNamed(a.planAfter, "light_volumes").culled);
  EXPECT_EQ(passNamed(a.planAfter, "light_volumes").reason, "disabled");
  // Its in-place output passes through: tonemap still reaches the lit target.
  EXPECT_FALSE(passNamed(a.planAfter, "tonemap").culled);
  EXPECT_FALSE(passNamed(a.planAfter, "ambient").culled);
}

TEST(AdaptToScene, PointLightsKeepTheLightVolumePass) {
  Scene scene = cubeScene();
  PointLight l;
  l.position = {0, 1, 0};
  scene.pointLights.push_back(l);
  Adapted a = adapt("deferred-light-volumes.json", scene);
  EXPECT_FALSE(passNamed(a.planAfter, "light_volumes").culled);
  // Markers are still drawn, so the forward pass and its depth blit stay.
  EXPECT_FALSE(passNamed(a.planAfter, "light_boxes").culled);
  EXPECT_FALSE(passNamed(a.planAfter, "depth_blit").culled);
}

TEST(AdaptToScene, NoBlendMaterialsAndNoLightsDropTheForwardPassAndItsDepthBlit) {
  Scene scene = cubeScene();
  ASSERT_FALSE(scene.hasBlendMaterials());
  Adapted a = adapt("deferred-pbr.json", scene);
  EXPECT_FALSE(passNamed(a.planBefore, "forward").culled);
  EXPECT_TRUE(passNamed(a.planAfter, "forward").culled);
  // Nothing reads the blitted depth any more: the compiler culls the blit and
  // allocates no forward depth buffer.
  EXPECT_TRUE(passNamed(a.planAfter, "depth_blit").culled);
  EXPECT_FALSE(resourceNamed(a.planAfter, "forwardDepth").physical.valid());
  EXPECT_LT(a.planAfter.allocatedBytes, a.planBefore.allocatedBytes);
}

TEST(AdaptToScene, BlendMaterialsKeepTheForwardBlendPass) {
  Scene scene = cubeScene();
  Material glass;
  glass.alphaMode = AlphaMode::blend;
  glass.metallicFactor = 0.25f;
  glass.roughnessFactor = 0.75f;
  scene.materials.push_back(glass);
  Primitive p = scene.primitives[0];
  p.material = 1;
  scene.primitives.push_back(p);
  Adapted a = adapt("deferred-pbr.json", scene);
  EXPECT_FALSE(passNamed(a.planAfter, "forward").culled);
  const size_t forward = 3;
  ASSERT_EQ(a.after.graph.passes[forward].name, "forward");
  EXPECT_TRUE(a.after.params[forward].getBool("blend", false));
  EXPECT_FALSE(a.after.params[forward].getBool("markers", true));  // still no point lights
}

size_t passIndex(const PipelineConfig& c, const std::string& name) {
  for (size_t i = 0; i < c.graph.passes.size(); ++i)
    if (c.graph.passes[i].name == name) return i;
  ADD_FAILURE() << "no pass " << name;
  return 0;
}

// Light markers: a scene-file light gets one, at most 1/32 of the scene's
// bounding radius in half extent; a glTF file's own lamps get none.
TEST(AdaptToScene, LightMarkersAreSizedFromTheSceneAndLeftToGltfLamps) {
  Scene big = cubeScene();
  big.primitives[0].bounds.expand(glm::vec3(20.0f));  // radius ~35: the pipeline's 0.125 stays
  big.pointLights.push_back(PointLight{});
  Adapted a = adapt("deferred-pbr.json", big);
  const size_t forward = passIndex(a.after, "forward");
  EXPECT_TRUE(a.after.params[forward].getBool("markers", false));
  EXPECT_DOUBLE_EQ(a.after.params[forward].getNumber("marker_size", -1), 0.125);

  Scene small = cubeScene();  // a unit cube: radius sqrt(3)/2
  small.pointLights.push_back(PointLight{});
  a = adapt("deferred-pbr.json", small);
  EXPECT_TRUE(a.after.params[forward].getBool("markers", false));
  EXPECT_NEAR(a.after.params[forward].getNumber("marker_size", -1), std::sqrt(3.0) / 2.0 / 32.0, 1e-6);

  // LightsPunctualLamp: its spot light sits inside a lamp shade 0.1 across.
  Scene lamp = loadGltf(std::string(RGRAPH_ASSETS_DIR) + "/gltf/LightsPunctualLamp/LightsPunctualLamp.gltf");
  ASSERT_TRUE(lamp.hasPointLights());
  for (const auto& l : lamp.pointLights) EXPECT_FALSE(l.marker);
  a = adapt("deferred-pbr.json", lamp);
  EXPECT_FALSE(a.after.params[forward].getBool("markers", true));
  // One scene-file light among them brings the markers back.
  lamp.pointLights.push_back(PointLight{});
  a = adapt("deferred-pbr.json", lamp);
  EXPECT_TRUE(a.after.params[forward].getBool("markers", false));
}

TEST(AdaptToScene, OneMetallicRoughnessDropsTheMaterialTarget) {
  Scene scene = cubeScene();
  ASSERT_FALSE(scene.hasMetallicRoughnessVariation());
  Adapted a = adapt("deferred-pbr.json", scene);
  EXPECT_TRUE(resourceNamed(a.planBefore, "gMetalRough").physical.valid());
  EXPECT_FALSE(resourceNamed(a.planAfter, "gMetalRough").physical.valid());
  EXPECT_FALSE(resourceNamed(a.planAfter, "gMetalRough").firstPass.valid());
  // PBR layout: 4 x rgba16f + depth32f = 36 bytes, + the optional emissive and
  // reflectance targets (rgba16f each) as shipped = 52; this scene needs
  // neither, nor the material target: 28.
  EXPECT_EQ(gbufferBytesPerPixel(a.before, a.planBefore, processRegistry()), 52u);
  EXPECT_EQ(gbufferBytesPerPixel(a.after, a.planAfter, processRegistry()), 28u);
  // The lighting pass gets the scene's values instead.
  const size_t lighting = 1;
  ASSERT_EQ(a.after.graph.passes[lighting].name, "lighting");
  EXPECT_TRUE(a.after.params[lighting].getBool("constant_material", false));
  EXPECT_DOUBLE_EQ(a.after.params[lighting].getNumber("metallic", -1), 0.25);
  EXPECT_DOUBLE_EQ(a.after.params[lighting].getNumber("roughness", -1), 0.75);
}

TEST(AdaptToScene, MetallicRoughnessVariationKeepsTheMaterialTarget) {
  Scene scene = cubeScene();
  Material other = scene.materials[0];
  other.roughnessFactor = 0.2f;
  scene.materials.push_back(other);
  Primitive p = scene.primitives[0];
  p.material = 1;
  scene.primitives.push_back(p);
  Adapted a = adapt("deferred-pbr.json", scene);
  EXPECT_TRUE(resourceNamed(a.planAfter, "gMetalRough").physical.valid());
  EXPECT_EQ(gbufferBytesPerPixel(a.after, a.planAfter, processRegistry()), 36u);
}

TEST(AdaptToScene, NormalMapsAreAFeatureOfTheScene) {
  // No normal maps: no tangents in the meshes (the GPU upload then carries no
  // tangent attribute and the geometry pass compiles without normal mapping).
  Scene plain = loadGltf(std::string(RGRAPH_ASSETS_DIR) + "/gltf/Box/Box.glb");
  EXPECT_FALSE(sceneFeatures(plain).normalMaps);
  for (const auto& m : plain.meshes) EXPECT_FALSE(m.hasTangents());
  Scene mapped = loadGltf(std::string(RGRAPH_ASSETS_DIR) + "/gltf/NormalTangentMirrorTest/NormalTangentMirrorTest.glb");
  EXPECT_TRUE(sceneFeatures(mapped).normalMaps);
}

TEST(AdaptToScene, TheLearnOpenGLSceneNeedsEverythingItsPipelineHas) {
  Adapted a = adapt("deferred-light-volumes.json", makeLearnOpenGLScene());
  for (const auto& p : a.planAfter.passes) EXPECT_FALSE(p.culled) << p.name;
  // learnopengl layout has no material target to drop; the scene emits no
  // light: only the emissive target (r11g11b10f, 4 bytes) goes.
  EXPECT_EQ(gbufferBytesPerPixel(a.before, a.planBefore, processRegistry()),
            gbufferBytesPerPixel(a.after, a.planAfter, processRegistry()) + 4u);
}

// The optional G-buffer targets (gbuffer_layout.cpp): a scene with no
// emitting material gets no emissive target, one with an emitting material
// keeps it; likewise reflectance for KHR_materials_specular.
TEST(AdaptToScene, EmissiveAndReflectanceTargetsFollowTheScene) {
  Scene plain = cubeScene();
  ASSERT_FALSE(sceneFeatures(plain).emissive);
  ASSERT_FALSE(sceneFeatures(plain).reflectance);
  Adapted a = adapt("deferred-pbr.json", plain);
  EXPECT_TRUE(resourceNamed(a.planBefore, "gEmissive").physical.valid());
  EXPECT_FALSE(resourceNamed(a.planAfter, "gEmissive").physical.valid());
  EXPECT_FALSE(resourceNamed(a.planAfter, "gReflectance").physical.valid());
  for (size_t i : {size_t(0), size_t(1)}) {  // geometry and lighting: off, slot unbound
    EXPECT_FALSE(a.after.params[i].getBool("emissive", true)) << a.after.graph.passes[i].name;
    for (const auto& use : a.after.graph.passes[i].uses) EXPECT_NE(use.slot, "emissive");
  }

  Scene glowing = cubeScene();
  glowing.materials[0].emissiveFactor = {2.0f, 1.0f, 0.5f};
  ASSERT_TRUE(sceneFeatures(glowing).emissive);
  Adapted e = adapt("deferred-pbr.json", glowing);
  EXPECT_TRUE(resourceNamed(e.planAfter, "gEmissive").physical.valid());
  EXPECT_FALSE(resourceNamed(e.planAfter, "gReflectance").physical.valid());
  // 28 (one metallic/roughness: no material target) + 8 (rgba16f emissive).
  const uint32_t withEmissive = gbufferBytesPerPixel(e.after, e.planAfter, processRegistry());
  EXPECT_EQ(withEmissive, 36u);

  Scene specular = cubeScene();
  specular.materials[0].specularFactor = 0.5f;
  ASSERT_TRUE(sceneFeatures(specular).reflectance);
  Adapted r = adapt("deferred-pbr.json", specular);
  EXPECT_FALSE(resourceNamed(r.planAfter, "gEmissive").physical.valid());
  EXPECT_TRUE(resourceNamed(r.planAfter, "gReflectance").physical.valid());

  // Unlit materials emit their base colour and reflect nothing: both targets.
  Scene unlit = cubeScene();
  unlit.materials[0].unlit = true;
  EXPECT_TRUE(sceneFeatures(unlit).emissive);
  EXPECT_TRUE(sceneFeatures(unlit).reflectance);

  // compact: r11g11b10f emissive (4 bytes), rgba8 reflectance (4 bytes).
  Adapted c = adapt("deferred-compact.json", glowing);
  Adapted cp = adapt("deferred-compact.json", plain);
  const uint32_t compactWith = gbufferBytesPerPixel(c.after, c.planAfter, processRegistry());
  const uint32_t compactWithout = gbufferBytesPerPixel(cp.after, cp.planAfter, processRegistry());
  std::printf("[ measure  ] G-buffer bytes per pixel: pbr %u without emissive, %u with; compact %u, %u\n",
              gbufferBytesPerPixel(a.after, a.planAfter, processRegistry()), withEmissive, compactWithout,
              compactWith);
  EXPECT_EQ(compactWith, compactWithout + 4u);
}

}  // namespace
}  // namespace rgraph
