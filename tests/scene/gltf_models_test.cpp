// The glTF sample models in ../shared/assets/gltf load with the expected content.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/gtc/epsilon.hpp>

#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::asset;

namespace {

const Material* findMaterial(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return &m;
  return nullptr;
}

void expectSane(const Scene& s) {
  EXPECT_NO_THROW(s.validate());
  EXPECT_GT(s.triangleCount(), 0u);
  EXPECT_FALSE(s.bounds().empty());
  for (const MeshData& m : s.meshes) {
    std::string why;
    EXPECT_TRUE(m.valid(&why)) << m.name << ": " << why;
    for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f) << m.name;
  }
  for (const ImageData& im : s.images) {
    EXPECT_GT(im.width, 0);
    EXPECT_EQ(im.rgba.size(), size_t(im.width) * size_t(im.height) * 4);
  }
}

}  // namespace

TEST(GltfModels, BoxTransformsAreFlattened) {
  Scene s = loadGltf(asset("Box/Box.glb"));
  expectSane(s);
  ASSERT_EQ(s.primitives.size(), 1u);
  EXPECT_EQ(s.triangleCount(), 12u);
  EXPECT_EQ(s.meshes[0].vertexCount(), 24u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "Red");
  EXPECT_TRUE(s.textures.empty());
  // Box.glb: root node matrix rotates -90 degrees about X (Z-up -> Y-up): (x, y, z) -> (x, z, -y).
  const Primitive& p = s.primitives[0];
  const MeshData& m = s.meshes[size_t(p.mesh)];
  for (const glm::vec3& local : m.positions) {
    const glm::vec3 world(p.transform * glm::vec4(local, 1.0f));
    EXPECT_NEAR(world.x, local.x, 1e-6f);
    EXPECT_NEAR(world.y, local.z, 1e-6f);
    EXPECT_NEAR(world.z, -local.y, 1e-6f);
  }
  // A known corner: (0.5, 0.5, 0.5) in the mesh ends up at (0.5, 0.5, -0.5).
  bool found = false;
  for (const glm::vec3& local : m.positions) {
    if (glm::all(glm::epsilonEqual(local, glm::vec3(0.5f, 0.5f, 0.5f), 1e-6f))) {
      const glm::vec3 world(p.transform * glm::vec4(local, 1.0f));
      EXPECT_NEAR(glm::distance(world, glm::vec3(0.5f, 0.5f, -0.5f)), 0.0f, 1e-6f);
      found = true;
    }
  }
  EXPECT_TRUE(found);
  // Normals follow through the normal matrix and stay outward.
  const glm::mat3 nm = p.normalMatrix();
  for (size_t i = 0; i < m.vertexCount(); ++i) {
    const glm::vec3 wp(p.transform * glm::vec4(m.positions[i], 1.0f));
    const glm::vec3 wn = glm::normalize(nm * m.normals[i]);
    EXPECT_GT(glm::dot(wn, wp), 0.0f);
  }
  EXPECT_FALSE(p.mirrored());
  EXPECT_NEAR(s.bounds().min.x, -0.5f, 1e-6f);
  EXPECT_NEAR(s.bounds().max.z, 0.5f, 1e-6f);
  EXPECT_FALSE(s.hasBlendMaterials());
  EXPECT_FALSE(s.hasNormalMaps());
  EXPECT_FALSE(s.hasMetallicRoughnessVariation());
  EXPECT_FALSE(s.hasPointLights());
  EXPECT_FALSE(s.hasTextures());
  EXPECT_FALSE(s.hasCamera);
}

TEST(GltfModels, BoxTexturedHasAnSrgbBaseColorTexture) {
  Scene s = loadGltf(asset("BoxTextured/BoxTextured.glb"));
  expectSane(s);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  ASSERT_TRUE(m.baseColorTexture.valid());
  ASSERT_EQ(s.textures.size(), 1u);
  const SceneTexture& t = s.textures[size_t(m.baseColorTexture.texture)];
  const ImageData& im = s.images[size_t(t.image)];
  EXPECT_TRUE(im.srgb);
  EXPECT_EQ(im.width, 256);
  EXPECT_EQ(im.height, 256);
  EXPECT_TRUE(s.meshes[0].hasUv0);
  EXPECT_TRUE(s.hasTextures());
  EXPECT_FALSE(s.meshes[0].hasTangents());  // no normal map, no tangents
}

TEST(GltfModels, CubeWithExternalBufferAndTextures) {
  Scene s = loadGltf(asset("Cube/Cube.gltf"));
  expectSane(s);
  EXPECT_EQ(s.triangleCount(), 12u);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  ASSERT_TRUE(m.baseColorTexture.valid());
  ASSERT_TRUE(m.metallicRoughnessTexture.valid());
  EXPECT_TRUE(s.images[size_t(s.textures[size_t(m.baseColorTexture.texture)].image)].srgb);
  EXPECT_FALSE(s.images[size_t(s.textures[size_t(m.metallicRoughnessTexture.texture)].image)].srgb);
  EXPECT_EQ(s.images.size(), 2u);
  EXPECT_TRUE(s.hasMetallicRoughnessVariation());  // a metallic-roughness texture
  EXPECT_NEAR(s.bounds().max.x, 1.0f, 1e-5f);
}

TEST(GltfModels, MetalRoughSpheresSweepFactors) {
  Scene s = loadGltf(asset("MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb"));
  expectSane(s);
  EXPECT_TRUE(s.textures.empty());
  // 98 materials in the file, plus the default material for primitives without one.
  EXPECT_EQ(s.materials.size(), 99u);
  EXPECT_TRUE(s.hasMetallicRoughnessVariation());
  std::set<float> metallic, roughness;
  for (const Primitive& p : s.primitives) {
    metallic.insert(s.materials[size_t(p.material)].metallicFactor);
    roughness.insert(s.materials[size_t(p.material)].roughnessFactor);
  }
  EXPECT_GE(metallic.size(), 7u);
  EXPECT_GE(roughness.size(), 7u);
  EXPECT_GT(s.triangleCount(), 100000u);
}

TEST(GltfModels, NormalTangentMirrorTestHasNormalMapsAndTangents) {
  Scene s = loadGltf(asset("NormalTangentMirrorTest/NormalTangentMirrorTest.glb"));
  expectSane(s);
  EXPECT_TRUE(s.hasNormalMaps());
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  ASSERT_TRUE(m.normalTexture.valid());
  EXPECT_FALSE(s.images[size_t(s.textures[size_t(m.normalTexture.texture)].image)].srgb);
  ASSERT_EQ(s.primitives.size(), 1u);
  const MeshData& mesh = s.meshes[size_t(s.primitives[0].mesh)];
  ASSERT_TRUE(mesh.hasTangents());
  int positive = 0, negative = 0;
  for (size_t i = 0; i < mesh.vertexCount(); ++i) {
    const glm::vec3 t(mesh.tangents[i]);
    ASSERT_NEAR(glm::length(t), 1.0f, 1e-3f);
    ASSERT_TRUE(mesh.tangents[i].w == 1.0f || mesh.tangents[i].w == -1.0f);
    (mesh.tangents[i].w > 0 ? positive : negative)++;
  }
  EXPECT_GT(positive, 0);
  EXPECT_GT(negative, 0);  // mirrored UVs
}

// Generated tangents agree with the tangents the model ships with (direction and handedness).
TEST(GltfModels, GeneratedTangentsMatchTheFileTangents) {
  Scene s = loadGltf(asset("NormalTangentMirrorTest/NormalTangentMirrorTest.glb"));
  MeshData m = s.meshes[0];
  const std::vector<glm::vec4> file = m.tangents;
  m.tangents.clear();
  generateTangents(m);
  ASSERT_EQ(m.tangents.size(), file.size());
  size_t dirAgree = 0, wAgree = 0;
  for (size_t i = 0; i < file.size(); ++i) {
    if (glm::dot(glm::vec3(file[i]), glm::vec3(m.tangents[i])) > 0.9f) ++dirAgree;
    if (file[i].w == m.tangents[i].w) ++wAgree;
  }
  EXPECT_GE(double(dirAgree), 0.95 * double(file.size()));
  EXPECT_GE(double(wAgree), 0.95 * double(file.size()));
}

TEST(GltfModels, SuzanneLoads) {
  Scene s = loadGltf(asset("Suzanne/Suzanne.gltf"));
  expectSane(s);
  EXPECT_EQ(s.triangleCount(), 3936u);
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.images.size(), 2u);
  for (const ImageData& im : s.images) EXPECT_EQ(im.width, 1024);
  EXPECT_FALSE(s.hasNormalMaps());
  EXPECT_FALSE(s.meshes[0].hasTangents());  // the file has tangents but no normal map uses them
}

TEST(GltfModels, AlphaBlendModeTestHasBlendAndMaskMaterials) {
  Scene s = loadGltf(asset("AlphaBlendModeTest/AlphaBlendModeTest.glb"));
  expectSane(s);
  EXPECT_EQ(s.materials.size(), 6u);
  EXPECT_TRUE(s.hasBlendMaterials());
  EXPECT_TRUE(s.hasMaskMaterials());
  const Material* blend = findMaterial(s, "MatBlend");
  const Material* c25 = findMaterial(s, "MatCutoff25");
  const Material* c75 = findMaterial(s, "MatCutoff75");
  const Material* cdef = findMaterial(s, "MatCutoffDefault");
  const Material* opaque = findMaterial(s, "MatOpaque");
  ASSERT_TRUE(blend && c25 && c75 && cdef && opaque);
  EXPECT_EQ(blend->alphaMode, AlphaMode::blend);
  EXPECT_EQ(c25->alphaMode, AlphaMode::mask);
  EXPECT_NEAR(c25->alphaCutoff, 0.25f, 1e-6f);
  EXPECT_NEAR(c75->alphaCutoff, 0.75f, 1e-6f);
  EXPECT_NEAR(cdef->alphaCutoff, 0.5f, 1e-6f);
  EXPECT_EQ(opaque->alphaMode, AlphaMode::opaque);
  size_t blendDraws = 0;
  for (const Primitive& p : s.primitives)
    if (s.materials[size_t(p.material)].alphaMode == AlphaMode::blend) ++blendDraws;
  EXPECT_GT(blendDraws, 0u);
  EXPECT_LT(blendDraws, s.primitives.size());
}

TEST(GltfModels, TextureSettingsTestSamplers) {
  Scene s = loadGltf(asset("TextureSettingsTest/TextureSettingsTest.glb"));
  expectSane(s);
  EXPECT_EQ(s.materials.size(), 10u);
  std::set<int> wraps;
  for (const SceneTexture& t : s.textures) {
    wraps.insert(t.sampler.wrapS);
    wraps.insert(t.sampler.wrapT);
    EXPECT_TRUE(t.sampler.minFilter >= SamplerDesc::kNearest && t.sampler.minFilter <= SamplerDesc::kLinearMipmapLinear);
  }
  EXPECT_TRUE(wraps.count(SamplerDesc::kRepeat));
  EXPECT_TRUE(wraps.count(SamplerDesc::kClampToEdge));
  EXPECT_TRUE(wraps.count(SamplerDesc::kMirroredRepeat));
  const Material* ds = findMaterial(s, "DoubleSidedMaterial");
  const Material* ss = findMaterial(s, "SingleSidedMaterial");
  ASSERT_TRUE(ds && ss);
  EXPECT_TRUE(ds->doubleSided);
  EXPECT_FALSE(ss->doubleSided);
  // Several textures share one image (same colour space): images are not duplicated.
  EXPECT_LT(s.images.size(), s.textures.size());
  EXPECT_FALSE(s.hasMetallicRoughnessVariation());
}

TEST(GltfModels, LoadSceneAnyAddsCameraAndLightFramingTheModel) {
  Scene s = loadSceneAny(asset("Box/Box.glb"));
  EXPECT_TRUE(s.hasCamera);
  ASSERT_EQ(s.directionalLights.size(), 1u);
  EXPECT_TRUE(s.pointLights.empty());
  EXPECT_NEAR(s.camera.fovY, 45.0f, 1e-6f);
  EXPECT_GT(s.camera.position.z, s.bounds().max.z);             // +Z side
  EXPECT_GT(s.camera.position.y, s.bounds().center().y);        // slightly above
  EXPECT_LT(glm::distance(s.camera.target, s.bounds().center()), 1e-5f);
  const glm::mat4 vp = s.camera.viewProjection(1.0f);
  const Bounds b = s.bounds();
  for (int i = 0; i < 8; ++i) {
    glm::vec4 c = vp * glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z, 1.0f);
    ASSERT_GT(c.w, 0.0f);
    c /= c.w;
    EXPECT_LE(std::abs(c.x), 1.0f);
    EXPECT_LE(std::abs(c.y), 1.0f);
    EXPECT_LE(std::abs(c.z), 1.0f);
  }
}

TEST(GltfModels, EveryModelLoadsThroughLoadSceneAny) {
  for (const char* m : {"Box/Box.glb", "BoxTextured/BoxTextured.glb", "Cube/Cube.gltf", "NormalTangentMirrorTest/NormalTangentMirrorTest.glb",
                        "Suzanne/Suzanne.gltf", "AlphaBlendModeTest/AlphaBlendModeTest.glb", "TextureSettingsTest/TextureSettingsTest.glb"}) {
    Scene s = loadSceneAny(asset(m));
    EXPECT_TRUE(s.hasCamera) << m;
    EXPECT_FALSE(s.directionalLights.empty()) << m;
    EXPECT_NO_THROW(s.validate()) << m;
  }
}
