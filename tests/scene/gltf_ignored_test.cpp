// What a glTF file asks for and is not drawn: one warning per feature per
// file, naming the feature and what is drawn instead, logged and kept in
// Scene::warnings; a file without the feature gets none of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::asset;
using scenetest::TriangleGltf;

namespace {

// Every warning this file's table knows, by the words that start it (those of
// features now drawn, skins, animations, morph targets, COLOR_0, instancing,
// texture transforms and TEXCOORD_1, stay listed: no file may give them).
const std::vector<std::string> kAll = {
    "skins not applied: drawn in bind pose",
    "animations not played: drawn at rest",
    "morph targets not applied: drawn undeformed (default weights not applied)",
    "COLOR_0 ignored: base colour alone",
    "EXT_mesh_gpu_instancing ignored: one instance drawn",
    "KHR_texture_transform ignored: textures untransformed",
    "TEXCOORD_1 ignored:",
    "emissive ignored",  // drawn since issue 29: never warned
    "KHR_materials_clearcoat ignored:",
    "KHR_materials_transmission ignored:",
    "KHR_materials_sheen ignored:",
    "KHR_materials_ior ignored:",
    "KHR_materials_volume ignored:",
    "KHR_materials_iridescence ignored:",
    "KHR_draco_mesh_compression ignored:",
    "KHR_materials_specular textures ignored",  // read since issue 29
    "KHR_materials_unlit ignored",              // drawn since issue 29
};

// Loads `file`, then checks each of `expected` is logged exactly once and
// kept in Scene::warnings once, and no other warning of kAll appears.
void expectIgnored(const std::string& file, const std::vector<std::string>& expected) {
  SCOPED_TRACE(file);
  scenetest::LogCapture log;
  const Scene s = loadGltf(asset(file));
  const std::string text = log.text();
  std::string kept;
  for (const std::string& w : s.warnings) kept += w + "\n";
  for (const std::string& w : kAll) {
    const bool want = std::find(expected.begin(), expected.end(), w) != expected.end();
    EXPECT_EQ(scenetest::countOf(text, w), want ? 1u : 0u) << w << "\n--- log:\n" << text;
    EXPECT_EQ(scenetest::countOf(kept, w), want ? 1u : 0u) << w << "\n--- Scene::warnings:\n" << kept;
  }
}

}  // namespace

TEST(GltfIgnored, SamplesWarnOncePerIgnoredFeature) {
  // Drawn (tests/render/gltf_geometry_features_test.cpp): no warning.
  expectIgnored("VertexColorTest/VertexColorTest.glb", {});
  expectIgnored("TextureTransformTest/TextureTransformTest.gltf", {});
  expectIgnored("SimpleInstancing/SimpleInstancing.glb", {});
  // Drawn since issue 30 (tests/animation_gpu): no warning.
  expectIgnored("SimpleSkin/SimpleSkin.gltf", {});
  expectIgnored("SimpleMorph/SimpleMorph.gltf", {});
  expectIgnored("MorphPrimitivesTest/MorphPrimitivesTest.glb", {});
  expectIgnored("AnimatedCube/AnimatedCube.gltf", {});
  // Without any of them (emissive, KHR_materials_specular and its textures,
  // KHR_materials_unlit are drawn).
  expectIgnored("EmissiveStrengthTest/EmissiveStrengthTest.glb", {});
  expectIgnored("SpecularTest/SpecularTest.glb", {});
  expectIgnored("UnlitTest/UnlitTest.glb", {});
  expectIgnored("TextureCoordinateTest/TextureCoordinateTest.glb", {});
  expectIgnored("Box/Box.glb", {});
  expectIgnored("MeshPrimitiveModes/MeshPrimitiveModes.gltf", {});
}

class GltfIgnoredFiles : public scenetest::TempDirTest {};

TEST_F(GltfIgnoredFiles, MaterialExtensionsWarnAndTexCoordOneDoesNot) {
  TriangleGltf t;
  const std::vector<std::string> exts = {"KHR_materials_clearcoat", "KHR_materials_transmission", "KHR_materials_sheen",
                                         "KHR_materials_ior",       "KHR_materials_volume",       "KHR_materials_iridescence"};
  t.doc["extensionsUsed"] = exts;
  t.doc["images"] = json::array({{{"uri", "data:image/png;base64," + scenetest::base64(scenetest::tinyPng())}}});
  t.doc["textures"] = json::array({{{"source", 0}}});
  // Two materials naming texCoord 1 (drawn: no warning).
  t.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}},
                                    {{"occlusionTexture", {{"index", 0}, {"texCoord", 1}}}}});
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.doc["meshes"][0]["primitives"].push_back(t.doc["meshes"][0]["primitives"][0]);
  t.doc["meshes"][0]["primitives"][1]["material"] = 1;
  t.writeGltf(path("m.gltf"));
  scenetest::LogCapture log;
  const Scene s = loadGltf(path("m.gltf"));
  const std::string text = log.text();
  for (const std::string& e : exts) EXPECT_EQ(scenetest::countOf(text, e + " ignored: "), 1u) << e << "\n" << text;
  EXPECT_EQ(scenetest::countOf(text, "TEXCOORD_1 ignored"), 0u) << text;
  EXPECT_EQ(s.warnings.size(), exts.size()) << text;
}

TEST_F(GltfIgnoredFiles, LoadedThroughASceneFileTheWarningsAreKept) {
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  t.writeGltf(path("m.gltf"));
  scenetest::writeText(path("s.json"), R"({"models": [{"file": "m.gltf"}, {"file": "m.gltf"}]})");
  scenetest::LogCapture log;
  const Scene s = loadSceneAny(path("s.json"));
  // Per file: the same file twice is two files' worth.
  ASSERT_EQ(s.warnings.size(), 2u) << log.text();
  EXPECT_NE(s.warnings[0].find("KHR_materials_sheen ignored: drawn without sheen"), std::string::npos) << s.warnings[0];
}

TEST_F(GltfIgnoredFiles, AMissingTextureIsReportedOnce) {
  TriangleGltf t;
  t.doc["images"] = json::parse(R"([{"uri": "missing_texture.png"}])");
  t.doc["textures"] = json::parse(R"([{"source": 0}])");
  t.doc["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.writeGltf(path("m.gltf"));
  scenetest::LogCapture log;
  std::string error;
  try {
    loadGltf(path("m.gltf"));
  } catch (const RuntimeError& e) {
    error = e.what();
  }
  EXPECT_EQ(scenetest::countOf(error, "missing_texture.png"), 2u) << error;  // "image 0 ('missing_texture.png') ... file .../missing_texture.png"
  EXPECT_NE(error.find("missing or unreadable file " + path("missing_texture.png")), std::string::npos) << error;
  EXPECT_EQ(scenetest::countOf(log.text(), "missing_texture.png"), 0u) << log.text();
}
