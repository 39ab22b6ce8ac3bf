// glTF geometry and texturing read at load (drawn by GpuScene: the image
// tests are tests/render/gltf_geometry_features_test.cpp): COLOR_0 vertex
// colours in each allowed type, KHR_texture_transform per texture (and its
// texCoord override), TEXCOORD_1, EXT_mesh_gpu_instancing instances and the
// bounds that cover them; malformed values refused at their JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <glm/gtc/constants.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::asset;
using scenetest::TriangleGltf;

namespace {

class GltfGeometryFeatures : public scenetest::TempDirTest {
 protected:
  // Appends `bytes` as a new buffer view and an accessor over it; returns the accessor's index.
  static int addAccessor(TriangleGltf& t, const std::vector<uint8_t>& bytes, int componentType, const char* type,
                         size_t count, bool normalized = false) {
    scenetest::pad4(t.bin);
    const size_t offset = t.bin.size();
    t.bin.insert(t.bin.end(), bytes.begin(), bytes.end());
    scenetest::pad4(t.bin);
    t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
    json acc = {{"bufferView", t.doc["bufferViews"].size() - 1}, {"componentType", componentType}, {"count", count},
                {"type", type}};
    if (normalized) acc["normalized"] = true;
    t.doc["accessors"].push_back(acc);
    return int(t.doc["accessors"].size() - 1);
  }
  template <class T>
  static std::vector<uint8_t> bytesOf(const std::vector<T>& v) {
    std::vector<uint8_t> out;
    scenetest::append(out, v);
    return out;
  }
  std::string loadError(TriangleGltf& t) {
    t.writeGltf(path("m.gltf"));
    try {
      loadGltf(path("m.gltf"));
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "(loaded)";
  }
};

}  // namespace

// ---------------------------------------------------------------- COLOR_0

TEST_F(GltfGeometryFeatures, VertexColoursDecodeInEveryAllowedType) {
  struct Case {
    const char* name;
    std::vector<uint8_t> bytes;
    int componentType;
    const char* type;
    bool normalized;
    glm::vec4 expected1;  // vertex 1's colour
  };
  const Case cases[] = {
      {"float vec3", bytesOf(std::vector<float>{1, 0, 0, 0.25f, 0.5f, 0.75f, 0, 0, 1}), 5126, "VEC3", false,
       {0.25f, 0.5f, 0.75f, 1.0f}},
      {"float vec4", bytesOf(std::vector<float>{1, 0, 0, 1, 0.25f, 0.5f, 0.75f, 0.5f, 0, 0, 1, 1}), 5126, "VEC4", false,
       {0.25f, 0.5f, 0.75f, 0.5f}},
      {"unsigned byte vec4", {255, 0, 0, 255, 0, 51, 255, 102, 0, 0, 255, 255}, 5121, "VEC4", true,
       {0.0f, 0.2f, 1.0f, 0.4f}},
      {"unsigned short vec3", bytesOf(std::vector<uint16_t>{65535, 0, 0, 0, 13107, 65535, 0, 0, 65535}), 5123, "VEC3",
       true, {0.0f, 0.2f, 1.0f, 1.0f}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    TriangleGltf t;
    const int a = addAccessor(t, c.bytes, c.componentType, c.type, 3, c.normalized);
    t.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = a;
    t.writeGltf(path("m.gltf"));
    const Scene s = loadGltf(path("m.gltf"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const MeshData& m = s.meshes[0];
    ASSERT_EQ(m.colors.size(), 3u);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(m.colors[1][k], c.expected1[k], 1e-6f) << "component " << k;
    EXPECT_TRUE(s.hasVertexColors());
  }
}

TEST_F(GltfGeometryFeatures, VertexColoursSurviveFlatNormals) {
  // No NORMAL: the mesh is unwelded (3 vertices per triangle); colours follow.
  TriangleGltf t;
  const int a = addAccessor(t, bytesOf(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1}), 5126, "VEC3", 3);
  t.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = a;
  t.writeGltf(path("m.gltf"));
  const Scene s = loadGltf(path("m.gltf"));
  const MeshData& m = s.meshes[0];
  ASSERT_EQ(m.colors.size(), m.vertexCount());
  for (size_t i = 0; i < m.vertexCount(); ++i)
    EXPECT_EQ(m.colors[i], glm::vec4(glm::vec3(m.positions[i] == glm::vec3(0.0f) ? glm::vec3(1, 0, 0)
                                                : m.positions[i].x > 0.5f               ? glm::vec3(0, 1, 0)
                                                                                        : glm::vec3(0, 0, 1)),
                                     1.0f))
        << i;
}

TEST_F(GltfGeometryFeatures, VertexColoursOfAnotherTypeAreRefusedAtTheAttribute) {
  TriangleGltf t;
  const int a = addAccessor(t, {255, 0, 0, 0, 255, 0, 0, 0, 255}, 5121, "VEC3", 3, false);  // not normalized
  t.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = a;
  const std::string e = loadError(t);
  EXPECT_NE(e.find("/meshes/0/primitives/0/attributes/COLOR_0"), std::string::npos) << e;
  EXPECT_NE(e.find("COLOR_0 may be FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT"), std::string::npos) << e;
}

TEST(GltfGeometryFeaturesSample, VertexColorTestHasColouredMeshes) {
  const Scene s = loadGltf(asset("VertexColorTest/VertexColorTest.glb"));
  EXPECT_TRUE(s.hasVertexColors());
  size_t coloured = 0;
  for (const MeshData& m : s.meshes) coloured += m.hasColors();
  EXPECT_GE(coloured, 1u);
  EXPECT_LT(coloured, s.meshes.size());  // the labels and the reference squares have none
}

// ---------------------------------------------------------------- KHR_texture_transform, TEXCOORD_1

TEST_F(GltfGeometryFeatures, TextureTransformIsReadPerTexture) {
  TriangleGltf t;
  const int uv1 = addAccessor(t, bytesOf(std::vector<float>{0, 0, 1, 0, 0, 1}), 5126, "VEC2", 3);
  t.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = uv1;
  t.doc["images"] = json::array({{{"uri", "data:image/png;base64," + scenetest::base64(scenetest::tinyPng())}}});
  t.doc["textures"] = json::array({{{"source", 0}}});
  const json transform = {{"offset", {0.5, 0.0}}, {"rotation", glm::half_pi<double>()}, {"scale", {2.0, 3.0}},
                          {"texCoord", 1}};
  t.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                     {"occlusionTexture",
                                      {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}},
                                     {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}}});
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.writeGltf(path("m.gltf"));
  const Scene s = loadGltf(path("m.gltf"));
  const Material& m = s.materials.at(0);
  // Untouched: identity, texCoord 0.
  EXPECT_EQ(m.baseColorTexture.texCoord, 0);
  EXPECT_EQ(m.baseColorTexture.uvTransform(), glm::mat3x2(1.0f));
  // The emissive texture names texCoord 1 itself; the occlusion one through the extension.
  EXPECT_EQ(m.emissiveTexture.texCoord, 1);
  EXPECT_EQ(m.occlusionTexture.texCoord, 1);
  EXPECT_TRUE(m.usesUv1());
  EXPECT_EQ(m.occlusionTexture.offset, glm::vec2(0.5f, 0.0f));
  EXPECT_EQ(m.occlusionTexture.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_FLOAT_EQ(m.occlusionTexture.rotation, glm::half_pi<float>());
  // The extension's matrix: scale, then rotate (u, v) -> (v, -u) for a quarter
  // turn, then offset: (1, 0) -> (2, 0) -> (0, -2) -> (0.5, -2); (0, 1) -> (0, 3) -> (3, 0) -> (3.5, 0).
  const glm::mat3x2 x = m.occlusionTexture.uvTransform();
  const glm::vec2 a = x * glm::vec3(1, 0, 1), b = x * glm::vec3(0, 1, 1);
  EXPECT_NEAR(a.x, 0.5f, 1e-6f);
  EXPECT_NEAR(a.y, -2.0f, 1e-6f);
  EXPECT_NEAR(b.x, 3.5f, 1e-6f);
  EXPECT_NEAR(b.y, 0.0f, 1e-6f);
  ASSERT_EQ(s.meshes.at(0).uv1.size(), 3u);
  EXPECT_EQ(s.meshes[0].uv1[1], glm::vec2(1, 0));
}

TEST_F(GltfGeometryFeatures, TextureTransformValuesAreCheckedAtTheirPointer) {
  struct Case {
    json transform;
    const char* pointer;
    const char* message;
  };
  const Case cases[] = {
      {{{"offset", {1.0, 1e300}}}, "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset/1",
       "must be a finite number"},
      {{{"scale", {1.0}}}, "/extensions/KHR_texture_transform/scale", "expected an array of 2 numbers"},
      {{{"rotation", "a quarter"}}, "/extensions/KHR_texture_transform/rotation", "expected a number"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.transform.dump());
    TriangleGltf t;
    t.doc["images"] = json::array({{{"uri", "data:image/png;base64," + scenetest::base64(scenetest::tinyPng())}}});
    t.doc["textures"] = json::array({{{"source", 0}}});
    t.doc["materials"] = json::array({{{"pbrMetallicRoughness",
                                        {{"baseColorTexture",
                                          {{"index", 0}, {"extensions", {{"KHR_texture_transform", c.transform}}}}}}}}});
    t.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const std::string e = loadError(t);
    EXPECT_NE(e.find(c.pointer), std::string::npos) << e;
    EXPECT_NE(e.find(c.message), std::string::npos) << e;
  }
}

TEST(GltfGeometryFeaturesSample, TextureTransformTestTransformsItsTextures) {
  const Scene s = loadGltf(asset("TextureTransformTest/TextureTransformTest.gltf"));
  size_t transformed = 0;
  for (const Material& m : s.materials)
    transformed += m.baseColorTexture.valid() && m.baseColorTexture.uvTransform() != glm::mat3x2(1.0f);
  EXPECT_GE(transformed, 6u);  // offset, rotation, scale and their combinations
}

// ---------------------------------------------------------------- EXT_mesh_gpu_instancing

TEST_F(GltfGeometryFeatures, InstancesAreTranslationRotationScaleAndBoundsCoverThem) {
  TriangleGltf t;
  const int tr = addAccessor(t, bytesOf(std::vector<float>{0, 0, 0, 10, 0, 0, 0, 0, -5}), 5126, "VEC3", 3);
  const float h = std::sqrt(0.5f);  // a quarter turn about +Z
  const int rot = addAccessor(t, bytesOf(std::vector<float>{0, 0, 0, 1, 0, 0, h, h, 0, 0, 0, 1}), 5126, "VEC4", 3);
  const int sc = addAccessor(t, bytesOf(std::vector<float>{1, 1, 1, 2, 2, 2, 1, 1, 1}), 5126, "VEC3", 3);
  t.doc["nodes"][0]["translation"] = {0.0, 1.0, 0.0};
  t.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
      {"TRANSLATION", tr}, {"ROTATION", rot}, {"SCALE", sc}};
  t.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  t.writeGltf(path("m.gltf"));
  const Scene s = loadGltf(path("m.gltf"));
  ASSERT_EQ(s.primitives.size(), 1u);
  const Primitive& p = s.primitives[0];
  ASSERT_EQ(p.instances.size(), 3u);
  // Instance 1: the triangle's (1, 0, 0) corner turned to (0, 1, 0), scaled by 2, moved by (10, 0, 0), then the node's +1 in y.
  const glm::vec3 corner = glm::vec3(p.transform * p.instances[1] * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(corner.x, 10.0f, 1e-5f);
  EXPECT_NEAR(corner.y, 3.0f, 1e-5f);
  EXPECT_NEAR(corner.z, 0.0f, 1e-5f);
  // Bounds over all three: x from 0 to 10, y from 1 to 3, z from -5 to 0.
  EXPECT_NEAR(p.bounds.min.x, 0.0f, 1e-5f);
  EXPECT_NEAR(p.bounds.max.x, 10.0f, 1e-5f);
  EXPECT_NEAR(p.bounds.max.y, 3.0f, 1e-5f);
  EXPECT_NEAR(p.bounds.min.z, -5.0f, 1e-5f);
  EXPECT_TRUE(s.hasInstancing());
  EXPECT_EQ(s.triangleCount(), 3u);  // one triangle per instance
}

TEST_F(GltfGeometryFeatures, InstanceAttributesOfDifferentCountsAreRefused) {
  TriangleGltf t;
  const int tr = addAccessor(t, bytesOf(std::vector<float>{0, 0, 0, 1, 0, 0}), 5126, "VEC3", 2);
  const int sc = addAccessor(t, bytesOf(std::vector<float>{1, 1, 1, 1, 1, 1, 1, 1, 1}), 5126, "VEC3", 3);
  t.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {{"TRANSLATION", tr}, {"SCALE", sc}};
  const std::string e = loadError(t);
  EXPECT_NE(e.find("/nodes/0/extensions/EXT_mesh_gpu_instancing/attributes/SCALE"), std::string::npos) << e;
  EXPECT_NE(e.find("has 3 instances, another attribute 2"), std::string::npos) << e;
}

TEST(GltfGeometryFeaturesSample, SimpleInstancingHasOneDrawPerMeshWithItsInstances) {
  const Scene s = loadGltf(asset("SimpleInstancing/SimpleInstancing.glb"));
  ASSERT_GE(s.primitives.size(), 1u);
  size_t instances = 0;
  for (const Primitive& p : s.primitives) instances += p.instances.size();
  std::printf("[ measure  ] SimpleInstancing: %zu primitives, %zu instances\n", s.primitives.size(), instances);
  EXPECT_GT(instances, 100u);
  // The bounds cover every instance, far more than one cube.
  const Bounds one = s.meshes[size_t(s.primitives[0].mesh)].bounds.transformed(s.primitives[0].transform);
  EXPECT_GT(s.bounds().radius(), 4.0f * one.radius());
}
