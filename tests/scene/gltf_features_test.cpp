// glTF features on small generated files: attribute layouts, index types,
// missing normals, hierarchy, lights, cameras, textures, sparse accessors.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::TriangleGltf;

namespace {
class GltfFeatures : public scenetest::TempDirTest {
 protected:
  Scene load(TriangleGltf& t, const std::string& name = "t.gltf") {
    t.writeGltf(path(name));
    return loadGltf(path(name));
  }
};

std::string pngDataUri() { return "data:image/png;base64," + scenetest::base64(scenetest::tinyPng()); }
}  // namespace

TEST_F(GltfFeatures, MissingNormalsBecomeFlatNormals) {
  TriangleGltf t;  // no NORMAL attribute
  Scene s = load(t);
  ASSERT_EQ(s.meshes.size(), 1u);
  for (const glm::vec3& n : s.meshes[0].normals) EXPECT_NEAR(glm::distance(n, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);

  // A quad folded along its diagonal: shared vertices are unwelded so each face keeps its own normal.
  TriangleGltf q;
  q.bin.clear();
  scenetest::append(q.bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1});
  scenetest::append(q.bin, std::vector<uint16_t>{0, 1, 2, 2, 1, 3});
  q.doc["accessors"][0]["count"] = 4;
  q.doc["accessors"][0]["max"] = {1, 1, 1};
  q.doc["accessors"][1]["count"] = 6;
  q.doc["bufferViews"][0]["byteLength"] = 48;
  q.doc["bufferViews"][1] = {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}};
  Scene f = load(q, "quad.gltf");
  const MeshData& m = f.meshes[0];
  EXPECT_EQ(m.vertexCount(), 6u);
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_NEAR(glm::distance(m.normals[0], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  const glm::vec3 second = glm::normalize(glm::cross(glm::vec3(1, 0, 0) - glm::vec3(0, 1, 0), glm::vec3(1, 1, 1) - glm::vec3(0, 1, 0)));
  EXPECT_NEAR(glm::distance(m.normals[3], second), 0.0f, 1e-5f);
}

TEST_F(GltfFeatures, InterleavedAttributesWithByteStride) {
  TriangleGltf t;
  t.bin.clear();
  // position, normal interleaved (stride 24), then indices.
  scenetest::append(t.bin, std::vector<float>{0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1});
  scenetest::append(t.bin, std::vector<uint16_t>{0, 1, 2});
  scenetest::pad4(t.bin);
  t.doc["bufferViews"][0] = {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 72}, {"byteStride", 24}};
  t.doc["bufferViews"][1] = {{"buffer", 0}, {"byteOffset", 72}, {"byteLength", 6}};
  t.doc["accessors"][0]["max"] = {2, 2, 0};
  t.doc["accessors"].push_back({{"bufferView", 0}, {"byteOffset", 12}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  t.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
  Scene s = load(t);
  const MeshData& m = s.meshes[0];
  ASSERT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.positions[1], glm::vec3(2, 0, 0));
  EXPECT_EQ(m.positions[2], glm::vec3(0, 2, 0));
  for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  EXPECT_EQ(m.bounds.max, glm::vec3(2, 2, 0));
}

TEST_F(GltfFeatures, IndexComponentTypes) {
  for (int ct : {5121, 5123, 5125}) {
    TriangleGltf t;
    t.bin.resize(36);
    if (ct == 5121) scenetest::append(t.bin, std::vector<uint8_t>{2, 1, 0});
    if (ct == 5123) scenetest::append(t.bin, std::vector<uint16_t>{2, 1, 0});
    if (ct == 5125) scenetest::append(t.bin, std::vector<uint32_t>{2, 1, 0});
    const size_t len = t.bin.size() - 36;
    scenetest::pad4(t.bin);
    t.doc["accessors"][1]["componentType"] = ct;
    t.doc["bufferViews"][1]["byteLength"] = len;
    Scene s = load(t, "idx" + std::to_string(ct) + ".gltf");
    // No normals in the file: flat normals unweld the triangle in index order.
    const MeshData& m = s.meshes[0];
    ASSERT_EQ(m.vertexCount(), 3u);
    EXPECT_EQ(m.positions[0], glm::vec3(0, 1, 0)) << ct;
    EXPECT_EQ(m.positions[1], glm::vec3(1, 0, 0)) << ct;
    EXPECT_EQ(m.positions[2], glm::vec3(0, 0, 0)) << ct;
    EXPECT_NEAR(glm::distance(m.normals[0], glm::vec3(0, 0, -1)), 0.0f, 1e-6f) << ct;  // reversed winding faces -Z
  }
}

TEST_F(GltfFeatures, NonIndexedGetsGeneratedIndices) {
  TriangleGltf t;
  t.doc["meshes"][0]["primitives"][0].erase("indices");
  Scene s = load(t);
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST_F(GltfFeatures, NormalizedTexcoords) {
  TriangleGltf t;
  const size_t at = t.bin.size();
  scenetest::append(t.bin, std::vector<uint8_t>{0, 0, 255, 0, 0, 255});
  scenetest::pad4(t.bin);
  t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 6}});
  t.doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC2"}});
  t.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
  Scene s = load(t);
  const MeshData& m = s.meshes[0];
  EXPECT_TRUE(m.hasUv0);
  EXPECT_EQ(m.uv0[1], glm::vec2(1, 0));
  EXPECT_EQ(m.uv0[2], glm::vec2(0, 1));
}

TEST_F(GltfFeatures, NonTrianglePrimitivesAreSkipped) {
  TriangleGltf t;
  json lines = t.doc["meshes"][0]["primitives"][0];
  lines["mode"] = 1;  // LINES
  t.doc["meshes"][0]["primitives"].push_back(lines);
  Scene s = load(t);
  EXPECT_EQ(s.primitives.size(), 1u);
  EXPECT_EQ(s.triangleCount(), 1u);
}

TEST_F(GltfFeatures, NodeHierarchyIsFlattened) {
  TriangleGltf t;
  t.doc["nodes"] = json::parse(R"([
    {"translation": [1, 2, 3], "children": [1]},
    {"rotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "scale": [2, 2, 2], "mesh": 0, "name": "child"}
  ])");
  Scene s = load(t);
  ASSERT_EQ(s.primitives.size(), 1u);
  const glm::mat4 expected = glm::translate(glm::mat4(1), glm::vec3(1, 2, 3)) *
                             glm::rotate(glm::mat4(1), glm::radians(90.0f), glm::vec3(0, 1, 0)) * glm::scale(glm::mat4(1), glm::vec3(2));
  const Primitive& p = s.primitives[0];
  EXPECT_EQ(p.name, "child");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(p.transform[c][r], expected[c][r], 1e-5f);
  // Local (1,0,0) -> rotated to (0,0,-1), scaled 2, translated: (1, 2, 1).
  const glm::vec3 w(p.transform * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(glm::distance(w, glm::vec3(1, 2, 1)), 0.0f, 1e-5f);
  EXPECT_NEAR(p.bounds.min.z, 1.0f, 1e-5f);
  EXPECT_NEAR(p.bounds.max.z, 3.0f, 1e-5f);
}

TEST_F(GltfFeatures, MatrixNodesAndMirroring) {
  TriangleGltf t;
  t.doc["nodes"][0]["matrix"] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
  Scene s = load(t);
  const Primitive& p = s.primitives[0];
  EXPECT_TRUE(p.mirrored());
  EXPECT_NEAR(glm::distance(glm::vec3(p.transform * glm::vec4(1, 0, 0, 1)), glm::vec3(4, 0, 0)), 0.0f, 1e-6f);
}

TEST_F(GltfFeatures, NodesWithoutScenesAreAllRoots) {
  TriangleGltf t;
  t.doc.erase("scene");
  t.doc.erase("scenes");
  t.doc["nodes"] = json::parse(R"([{"mesh": 0}, {"mesh": 0, "translation": [3, 0, 0]}])");
  Scene s = load(t);
  EXPECT_EQ(s.primitives.size(), 2u);
  EXPECT_EQ(s.meshes.size(), 1u);  // the mesh is shared by both draws
  EXPECT_EQ(s.triangleCount(), 2u);
}

TEST_F(GltfFeatures, LightsPunctualAndCamera) {
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  t.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::parse(R"([
    {"type": "point", "color": [1, 0.5, 0.25], "intensity": 2, "range": 5},
    {"type": "directional", "color": [1, 1, 1], "intensity": 3},
    {"type": "point", "intensity": 1},
    {"type": "spot", "intensity": 1, "spot": {"outerConeAngle": 0.5}}
  ])");
  t.doc["cameras"] = json::parse(R"([{"type": "perspective", "perspective": {"yfov": 0.7853981634, "znear": 0.5, "zfar": 50}}])");
  t.doc["nodes"] = json::parse(R"([
    {"mesh": 0, "children": [1, 2, 3, 4, 5]},
    {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476], "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"translation": [0, 0, 10], "camera": 0},
    {"extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"extensions": {"KHR_lights_punctual": {"light": 3}}}
  ])");
  Scene s = load(t);
  ASSERT_EQ(s.pointLights.size(), 3u);  // two point lights and the spot light
  ASSERT_EQ(s.directionalLights.size(), 1u);
  EXPECT_FALSE(s.pointLights[0].spot);
  EXPECT_FALSE(s.pointLights[1].spot);
  // The spot light keeps its cone (radians -> degrees; inner defaults to 0)
  // and points down its node's -Z.
  const PointLight& spot = s.pointLights[2];
  EXPECT_TRUE(spot.spot);
  EXPECT_NEAR(spot.outerConeDeg, 0.5f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_EQ(spot.innerConeDeg, 0.0f);
  EXPECT_NEAR(glm::distance(spot.direction, glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  const PointLight& p = s.pointLights[0];
  EXPECT_EQ(p.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(p.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(p.intensity, 2.0f);
  EXPECT_EQ(p.radius, 5.0f);  // range -> radius
  // Without a range the radius comes from the attenuation (constant 1, quadratic 1).
  EXPECT_NEAR(s.pointLights[1].radius, lightRadius(s.pointLights[1]), 1e-6f);
  EXPECT_NEAR(s.pointLights[1].radius, std::sqrt(256.0f / 5.0f - 1.0f), 1e-4f);
  // -Z rotated -90 degrees about X points down.
  EXPECT_NEAR(glm::distance(s.directionalLights[0].direction, glm::vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(s.directionalLights[0].intensity, 3.0f);
  ASSERT_TRUE(s.hasCamera);
  EXPECT_NEAR(s.camera.fovY, 45.0f, 1e-4f);
  EXPECT_EQ(s.camera.near, 0.5f);
  EXPECT_EQ(s.camera.far, 50.0f);
  EXPECT_EQ(s.camera.position, glm::vec3(0, 0, 10));
  EXPECT_NEAR(glm::distance(s.camera.forward(), glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  EXPECT_TRUE(s.hasPointLights());
  // loadSceneAny keeps the file's camera and lights.
  Scene any = loadSceneAny(path("t.gltf"));
  EXPECT_EQ(any.directionalLights.size(), 1u);
  EXPECT_EQ(any.camera.position, glm::vec3(0, 0, 10));
}

TEST_F(GltfFeatures, TexturesSamplersAndGeneratedTangents) {
  TriangleGltf t;
  const size_t at = t.bin.size();
  scenetest::append(t.bin, std::vector<float>{0, 1, 1, 1, 0, 0});  // glTF UVs: v grows downwards
  t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 24}});
  t.doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  t.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.doc["images"] = {{{"uri", pngDataUri()}}};
  t.doc["samplers"] = json::parse(R"([{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728, "minFilter": 9729}])");
  t.doc["textures"] = json::parse(R"([{"source": 0, "sampler": 0}, {"source": 0}])");
  t.doc["materials"] = json::parse(R"([{
    "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [0.5, 0.5, 0.5, 1],
                             "metallicFactor": 0.25, "roughnessFactor": 0.75},
    "normalTexture": {"index": 1, "scale": 0.5},
    "emissiveFactor": [1, 0, 0],
    "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": true
  }])");
  Scene s = load(t);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  EXPECT_EQ(m.metallicFactor, 0.25f);
  EXPECT_EQ(m.roughnessFactor, 0.75f);
  EXPECT_EQ(m.emissiveFactor, glm::vec3(1, 0, 0));
  EXPECT_EQ(m.normalScale, 0.5f);
  EXPECT_EQ(m.alphaMode, AlphaMode::mask);
  EXPECT_NEAR(m.alphaCutoff, 0.3f, 1e-6f);
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.specular, 0.5f);
  // One glTF image used as sRGB (base colour) and linear (normal map): two images.
  ASSERT_EQ(s.images.size(), 2u);
  const SceneTexture& bc = s.textures[size_t(m.baseColorTexture.texture)];
  const SceneTexture& nt = s.textures[size_t(m.normalTexture.texture)];
  EXPECT_TRUE(s.images[size_t(bc.image)].srgb);
  EXPECT_FALSE(s.images[size_t(nt.image)].srgb);
  EXPECT_EQ(bc.sampler.wrapS, SamplerDesc::kClampToEdge);
  EXPECT_EQ(bc.sampler.wrapT, SamplerDesc::kMirroredRepeat);
  EXPECT_EQ(bc.sampler.magFilter, SamplerDesc::kNearest);
  EXPECT_EQ(bc.sampler.minFilter, SamplerDesc::kLinear);
  EXPECT_FALSE(bc.sampler.usesMipmaps());
  EXPECT_EQ(nt.sampler, SamplerDesc{});  // no sampler: defaults
  // Pixels decoded to RGBA8, first row first: red, green / blue, white.
  const ImageData& im = s.images[size_t(bc.image)];
  ASSERT_EQ(im.width, 2);
  ASSERT_EQ(im.height, 2);
  EXPECT_EQ(std::vector<uint8_t>(im.rgba.begin(), im.rgba.begin() + 4), (std::vector<uint8_t>{255, 0, 0, 255}));
  EXPECT_EQ(std::vector<uint8_t>(im.rgba.begin() + 8, im.rgba.begin() + 12), (std::vector<uint8_t>{0, 0, 255, 255}));
  // The normal map made the loader generate tangents: +X tangent, bitangent "up the image" = +Y here.
  const MeshData& mesh = s.meshes[0];
  ASSERT_TRUE(mesh.hasTangents());
  for (size_t i = 0; i < mesh.vertexCount(); ++i) {
    EXPECT_NEAR(glm::distance(glm::vec3(mesh.tangents[i]), glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    const glm::vec3 bitangent = mesh.tangents[i].w * glm::cross(mesh.normals[i], glm::vec3(mesh.tangents[i]));
    EXPECT_NEAR(glm::distance(bitangent, glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
  }
  EXPECT_TRUE(s.hasNormalMaps());
  EXPECT_TRUE(s.hasMaskMaterials());
}

TEST_F(GltfFeatures, SparseAccessor) {
  TriangleGltf t;
  const size_t at = t.bin.size();
  scenetest::append(t.bin, std::vector<uint16_t>{2, 0});        // sparse index: vertex 2
  scenetest::append(t.bin, std::vector<float>{0, 5, 0});       // its new value
  t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 2}});
  t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 4}, {"byteLength", 12}});
  t.doc["accessors"][0]["sparse"] = json::parse(R"({"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                                     "values": {"bufferView": 3}})");
  Scene s = load(t);
  EXPECT_EQ(s.meshes[0].positions[2], glm::vec3(0, 5, 0));
  EXPECT_EQ(s.meshes[0].positions[1], glm::vec3(1, 0, 0));

  // A sparse index beyond the accessor's count is rejected.
  std::memcpy(t.bin.data() + at, std::vector<uint16_t>{9}.data(), 2);
  t.writeGltf(path("bad_sparse.gltf"));
  EXPECT_THROW(loadGltf(path("bad_sparse.gltf")), RuntimeError);
}

TEST_F(GltfFeatures, UnsupportedRequiredExtension) {
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  t.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  t.writeGltf(path("draco.gltf"));
  try {
    loadGltf(path("draco.gltf"));
    ADD_FAILURE() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("KHR_draco_mesh_compression"), std::string::npos) << e.what();
  }
}

TEST_F(GltfFeatures, SpotLightConeAndDirection) {
  // A spot light on a node turned -90 degrees about X (its -Z points down),
  // both angles given; a second one with the extension's default cone.
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  t.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::parse(R"([
    {"type": "spot", "color": [1, 0.8, 0.6], "intensity": 4, "range": 7,
     "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
    {"type": "spot", "spot": {}}
  ])");
  t.doc["nodes"] = json::parse(R"([
    {"mesh": 0, "children": [1, 2]},
    {"translation": [0, 5, 0], "rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"extensions": {"KHR_lights_punctual": {"light": 1}}}
  ])");
  Scene s = load(t);
  ASSERT_EQ(s.pointLights.size(), 2u);
  const PointLight& a = s.pointLights[0];
  EXPECT_TRUE(a.spot);
  EXPECT_EQ(a.position, glm::vec3(0, 5, 0));
  EXPECT_NEAR(glm::distance(a.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(a.innerConeDeg, 0.2f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_NEAR(a.outerConeDeg, 0.6f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_EQ(a.radius, 7.0f);  // range -> the cone's length
  EXPECT_EQ(a.intensity, 4.0f);
  const PointLight& b = s.pointLights[1];
  EXPECT_TRUE(b.spot);
  EXPECT_EQ(b.innerConeDeg, 0.0f);
  EXPECT_NEAR(b.outerConeDeg, 45.0f, 1e-4f);
  EXPECT_NEAR(b.radius, lightRadius(b), 1e-6f);  // no range: the attenuation's cut-off, as for a point light
}

TEST_F(GltfFeatures, SpotLightConeOutOfRangeIsRefusedWithPointer) {
  auto refused = [&](const char* spot, const std::string& needle) {
    TriangleGltf t;
    t.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    t.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({json::parse(spot)});
    t.doc["nodes"] = json::parse(R"([{"mesh": 0, "children": [1]}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}])");
    try {
      load(t);
      ADD_FAILURE() << "expected a RuntimeError for " << spot;
    } catch (const RuntimeError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(needle), std::string::npos) << msg;
      EXPECT_NE(msg.find("t.gltf:"), std::string::npos) << msg;
    }
  };
  refused(R"({"type": "spot", "spot": {"outerConeAngle": 2.0}})",
          "/extensions/KHR_lights_punctual/lights/0/spot/outerConeAngle: must be in (0, pi/2] radians, got 2");
  refused(R"({"type": "spot", "spot": {"outerConeAngle": 0}})", "/lights/0/spot/outerConeAngle");
  refused(R"({"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.4}})",
          "/lights/0/spot/innerConeAngle: must be >= 0 and less than outerConeAngle (0.4), got 0.5");
  refused(R"({"type": "spot", "spot": {"innerConeAngle": -0.1}})", "/lights/0/spot/innerConeAngle");
}
