// Hostile glTF input (issue 8): deep node chains and deep JSON nesting (no
// stack overflow), buffer URIs that are folders or missing, values out of
// range (refused with file:line:column and the JSON path), the light cap,
// KHR_materials_specular, and loading from memory.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::TriangleGltf;

namespace {

class GltfHardening : public scenetest::TempDirTest {
 protected:
  // Loads `p` expecting a RuntimeError that names the file; returns the message.
  static std::string loadError(const std::string& p) {
    try {
      Scene s = loadGltf(p);
      ADD_FAILURE() << p << ": expected a RuntimeError, loaded " << s.primitives.size() << " primitives";
    } catch (const RuntimeError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(p, 0), 0u) << "message does not start with the file: " << msg;
      return msg;
    }
    return {};
  }
  std::string text(const std::string& name) const {
    const std::vector<uint8_t> b = scenetest::readBytes(path(name));
    return std::string(b.begin(), b.end());
  }
};

// "LINE:COL" of the byte right after the first `needle` in `text` (1-based).
std::string positionAfter(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  const size_t offset = at + needle.size();
  int line = 1;
  size_t lineStart = 0;
  for (size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line, lineStart = i + 1;
  return std::to_string(line) + ":" + std::to_string(offset - lineStart + 1);
}

void expectContains(const std::string& msg, const std::string& needle) {
  EXPECT_NE(msg.find(needle), std::string::npos) << "'" << needle << "' not in: " << msg;
}

// `count` nodes, each the only child of the one before, each translated by +1
// in x; the deepest carries the triangle. `closeCycle`: the deepest node also
// lists node 0 as its child.
json nodeChain(int count, bool closeCycle) {
  json nodes = json::array();
  for (int i = 0; i < count; ++i) {
    json node = {{"translation", {1, 0, 0}}};
    if (i + 1 < count) {
      node["children"] = {i + 1};
    } else {
      node["mesh"] = 0;
      if (closeCycle) node["children"] = {0};
    }
    nodes.push_back(std::move(node));
  }
  return nodes;
}

}  // namespace

// ------------------------------------------------------------ deep hierarchies and nesting

TEST_F(GltfHardening, DeepNodeChainLoads) {
  // Deep enough to overflow the 8 MiB stack of any recursive traversal (80 bytes a level).
  constexpr int kDepth = 100000;
  TriangleGltf t;
  t.doc["nodes"] = nodeChain(kDepth, false);
  t.writeGltf(path("chain.gltf"));
  const Scene s = loadGltf(path("chain.gltf"));
  ASSERT_EQ(s.primitives.size(), 1u);
  // Every level's transform is applied, in order.
  EXPECT_EQ(glm::vec3(s.primitives[0].transform[3]), glm::vec3(float(kDepth), 0.0f, 0.0f));
}

TEST_F(GltfHardening, DeepNodeCycleIsAnError) {
  TriangleGltf t;
  t.doc["nodes"] = nodeChain(20000, true);
  t.writeGltf(path("cycle.gltf"));
  expectContains(loadError(path("cycle.gltf")), "node 0 is its own ancestor (cycle in the node hierarchy)");
}

TEST_F(GltfHardening, DeepJsonNestingIsRefusedWithItsPosition) {
  TriangleGltf t;
  t.writeGltf(path("base.gltf"));
  const std::string base = text("base.gltf");
  ASSERT_EQ(base[0], '{');
  // extras: 100,000 nested arrays (tinygltf would recurse once per level).
  const std::string deep = "{\"extras\": " + std::string(100000, '[') + std::string(100000, ']') + ", " + base.substr(1);
  scenetest::writeText(path("deep.gltf"), deep);
  // The root object is level 1, so the 256th '[' (column 12 + 255) opens level 257.
  const std::string msg = loadError(path("deep.gltf"));
  expectContains(msg, path("deep.gltf") + ":1:267: values nested deeper than 256 levels are not supported");

  // The same JSON as the chunk of a .glb.
  const std::vector<uint8_t> glb = TriangleGltf::makeGlb(
      "{\"extras\": " + std::string(100000, '[') + std::string(100000, ']') + ", " + t.glbJson().substr(1), t.bin);
  scenetest::writeBytes(path("deep.glb"), glb.data(), glb.size());
  expectContains(loadError(path("deep.glb")), "JSON chunk, line 1:267: values nested deeper than 256");

  // 256 levels exactly are fine.
  scenetest::writeText(path("limit.gltf"), "{\"extras\": " + std::string(255, '[') + std::string(255, ']') + ", " + base.substr(1));
  EXPECT_EQ(loadGltf(path("limit.gltf")).triangleCount(), 1u);
}

// ------------------------------------------------------------ buffer URIs

TEST_F(GltfHardening, BufferUriProblemsAreNamed) {
  auto withUri = [&](const std::string& name, const std::string& uri) {
    TriangleGltf t;
    t.doc["buffers"][0]["uri"] = uri;
    t.doc["buffers"][0]["byteLength"] = t.bin.size();
    scenetest::writeText(path(name), t.doc.dump(2));
    return loadError(path(name));
  };
  std::filesystem::create_directories(dir_ / "folder.bin");
  std::string msg = withUri("folder.gltf", "folder.bin");  // was std::bad_alloc
  expectContains(msg, path("folder.bin"));
  expectContains(msg, "it is a folder, not a file");
  msg = withUri("missing.gltf", "missing.bin");
  expectContains(msg, path("missing.bin"));
  expectContains(msg, "no such file");
  scenetest::writeText(path("empty.bin"), "");
  expectContains(withUri("empty.gltf", "empty.bin"), "the file is empty");
  // (tinygltf joins even an absolute URI onto the base folder: a link reaches a device.)
  std::filesystem::create_symlink("/dev/null", dir_ / "device.bin");
  expectContains(withUri("device.gltf", "device.bin"), path("device.bin") + " : it is not a regular file");
  expectContains(withUri("nouri.gltf", ""), "'uri' is missing");
}

// ------------------------------------------------------------ values out of range

TEST_F(GltfHardening, OutOfRangeValuesAreRefusedWithPositionAndPointer) {
  struct Case {
    std::string set;  // where the bad value goes
    json value;
    std::string pointer;  // expected in the message
    std::string key;      // the bad value follows "key": in the text ("": an array element, position not checked here)
    std::string why;
  };
  const std::string mat = "/materials/0", pbr = "/materials/0/pbrMetallicRoughness", light = "/extensions/KHR_lights_punctual/lights/0";
  const std::vector<Case> cases = {
      {pbr + "/metallicFactor", 9, pbr + "/metallicFactor", "metallicFactor", "must be in [0, 1], got 9"},
      {pbr + "/roughnessFactor", -1, pbr + "/roughnessFactor", "roughnessFactor", "must be in [0, 1], got -1"},
      {pbr + "/baseColorFactor", {1, 2, 1, 1}, pbr + "/baseColorFactor/1", "", "must be in [0, 1], got 2"},
      {mat + "/emissiveFactor", {0, -0.5, 0}, mat + "/emissiveFactor/1", "", "must be in [0, 1], got -0.5"},
      {mat + "/alphaCutoff", -0.25, mat + "/alphaCutoff", "alphaCutoff", "must be in [0, 1], got -0.25"},
      {mat + "/occlusionTexture", {{"index", 0}, {"strength", 3}}, mat + "/occlusionTexture/strength", "strength",
       "must be in [0, 1], got 3"},
      {mat + "/extensions/KHR_materials_emissive_strength", {{"emissiveStrength", -2}},
       mat + "/extensions/KHR_materials_emissive_strength/emissiveStrength", "emissiveStrength", "must be >= 0, got -2"},
      {mat + "/extensions/KHR_materials_specular", {{"specularFactor", 1.5}}, mat + "/extensions/KHR_materials_specular/specularFactor",
       "specularFactor", "must be in [0, 1], got 1.5"},
      {light + "/intensity", -3, light + "/intensity", "intensity", "must be >= 0, got -3"},
      {light + "/range", -1, light + "/range", "range", "must be > 0, got -1"},
      {light + "/color", {2, 0, 0}, light + "/color/0", "", "must be in [0, 1], got 2"},
      {"/cameras/0/perspective/yfov", 0, "/cameras/0/perspective/yfov", "yfov", "must be in (0, pi) radians"},
      {"/cameras/0/perspective/znear", -1, "/cameras/0/perspective/znear", "znear", "must be > 0"},
      {"/asset/version", "3.0", "/asset/version", "version", "glTF 3.0 is not supported"},
      {"/asset/minVersion", "2.1", "/asset/minVersion", "minVersion", "the file needs glTF 2.1"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.set);
    TriangleGltf t;
    t.doc["materials"] = json::parse(R"([{"name": "m"}])");
    t.doc["meshes"][0]["primitives"][0]["material"] = 0;
    t.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::parse(R"([{"type": "point", "intensity": 1}])");
    t.doc["cameras"] = json::parse(R"([{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}])");
    t.doc["nodes"] = json::parse(R"([{"mesh": 0, "camera": 0, "extensions": {"KHR_lights_punctual": {"light": 0}}}])");
    t.doc["images"] = {{{"uri", "data:image/png;base64," + scenetest::base64(scenetest::tinyPng())}}};
    t.doc["textures"] = {{{"source", 0}}};
    t.doc[json::json_pointer(c.set)] = c.value;
    t.writeGltf(path("bad.gltf"));
    const std::string msg = loadError(path("bad.gltf"));
    if (!c.key.empty()) {
      // file:line:column of the value, then its pointer.
      expectContains(msg, path("bad.gltf") + ":" + positionAfter(text("bad.gltf"), "\"" + c.key + "\": ") + ": " + c.pointer + ": " + c.why);
    } else {
      expectContains(msg, ": " + c.pointer + ": " + c.why);
      EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(msg[path("bad.gltf").size() + 1]))) << "no line:column: " << msg;
    }
  }
}

TEST_F(GltfHardening, InRangeEdgesLoad) {
  TriangleGltf t;
  t.doc["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 1,
    "baseColorFactor": [0, 1, 0, 1]}, "emissiveFactor": [1, 1, 1], "alphaCutoff": 1,
    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}])");
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.doc["asset"]["version"] = "2.1";  // a newer minor version is readable by a 2.0 loader
  t.writeGltf(path("edges.gltf"));
  const Scene s = loadGltf(path("edges.gltf"));
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].metallicFactor, 0.0f);
  EXPECT_EQ(s.materials[0].roughnessFactor, 1.0f);
  EXPECT_EQ(s.materials[0].emissiveFactor, glm::vec3(4.0f));
  EXPECT_EQ(s.materials[0].alphaCutoff, 1.0f);
}

TEST_F(GltfHardening, TooManyLightsAreRefused) {
  TriangleGltf t;
  t.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array();
  for (size_t i = 0; i <= kMaxSceneLights; ++i) t.doc["extensions"]["KHR_lights_punctual"]["lights"].push_back({{"type", "point"}});
  t.writeGltf(path("lights.gltf"));
  const std::string msg = loadError(path("lights.gltf"));
  expectContains(msg, "/extensions/KHR_lights_punctual/lights: 100001 lights; at most 100000 are supported");
}

TEST_F(GltfHardening, DegenerateCameraUpIsReplacedWithAWarning) {
  TriangleGltf t;
  t.doc["cameras"] = json::parse(R"([{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}])");
  // Scale 0 along y flattens the camera's up vector to nothing.
  t.doc["nodes"] = json::parse(R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5], "scale": [1, 0, 1]}])");
  t.doc["scenes"][0]["nodes"] = {0, 1};
  t.writeGltf(path("camera.gltf"));
  scenetest::LogCapture log;
  const Scene s = loadGltf(path("camera.gltf"));
  ASSERT_TRUE(s.hasCamera);
  EXPECT_EQ(s.camera.up, s.camera.validUp());
  EXPECT_GT(glm::length(glm::cross(s.camera.forward(), s.camera.up)), 0.5f);
  const glm::mat4 v = s.camera.view();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(v[c][r]));
  expectContains(log.text(), path("camera.gltf") + ": node 1: the camera's up vector is parallel to its view direction");
}

// ------------------------------------------------------------ KHR_materials_specular

TEST_F(GltfHardening, MaterialsSpecularMapsOntoTheBlinnPhongSpecular) {
  TriangleGltf t;
  t.doc["extensionsUsed"] = {"KHR_materials_specular"};
  t.doc["materials"] = json::parse(R"([
    {"name": "none"},
    {"name": "defaults", "extensions": {"KHR_materials_specular": {}}},
    {"name": "factor", "extensions": {"KHR_materials_specular": {"specularFactor": 0.4}}},
    {"name": "color", "extensions": {"KHR_materials_specular": {"specularColorFactor": [0.5, 1.0, 0.25]}}},
    {"name": "both", "extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [0.2, 0.6, 0.4]}}},
    {"name": "off", "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
    {"name": "bright", "extensions": {"KHR_materials_specular": {"specularColorFactor": [4, 4, 4]}}}
  ])");
  t.writeGltf(path("specular.gltf"));
  const Scene s = loadGltf(path("specular.gltf"));
  ASSERT_EQ(s.materials.size(), 8u);  // 7 + the default for the material-less primitive
  EXPECT_EQ(s.materials[0].specular, 0.5f);
  EXPECT_EQ(s.materials[1].specular, 0.5f);  // the extension's defaults look like no extension
  EXPECT_FLOAT_EQ(s.materials[2].specular, 0.2f);
  EXPECT_FLOAT_EQ(s.materials[3].specular, 0.5f);   // the brightest channel
  EXPECT_FLOAT_EQ(s.materials[4].specular, 0.15f);  // 0.5 * 0.5 * 0.6
  EXPECT_EQ(s.materials[5].specular, 0.0f);
  EXPECT_EQ(s.materials[6].specular, 1.0f);  // capped
  // Cook-Torrance's inputs (Material, include/lighting.glsl's surfaceF0/F90): the factors as given.
  EXPECT_EQ(s.materials[0].specularFactor, 1.0f);
  EXPECT_EQ(s.materials[0].specularColorFactor, glm::vec3(1.0f));
  EXPECT_FALSE(s.materials[1].nonDefaultReflectance());
  EXPECT_FLOAT_EQ(s.materials[2].specularFactor, 0.4f);
  EXPECT_EQ(s.materials[4].specularColorFactor, glm::vec3(0.2f, 0.6f, 0.4f));
  EXPECT_EQ(s.materials[6].specularColorFactor, glm::vec3(4.0f));
  EXPECT_TRUE(s.materials[6].nonDefaultReflectance());
}

// SpecularTest's texture rows: specularTexture (linear, A) and
// specularColorTexture (sRGB) are read, not ignored.
TEST_F(GltfHardening, MaterialsSpecularTexturesAreRead) {
  const Scene s = loadGltf(scenetest::asset("SpecularTest/SpecularTest.glb"));
  auto named = [&](const std::string& n) -> const Material& {
    for (const Material& m : s.materials)
      if (m.name == n) return m;
    throw std::runtime_error("no material " + n);
  };
  const Material& tex = named("M2_SpecTex");
  ASSERT_TRUE(tex.specularTexture.valid());
  EXPECT_FALSE(s.images[static_cast<size_t>(s.textures[static_cast<size_t>(tex.specularTexture.texture)].image)].srgb);
  const Material& color = named("M4_whiteTex");
  ASSERT_TRUE(color.specularColorTexture.valid());
  EXPECT_TRUE(
      s.images[static_cast<size_t>(s.textures[static_cast<size_t>(color.specularColorTexture.texture)].image)].srgb);
}

// KHR_materials_unlit, even when required (UnlitTest): accepted, the
// materials marked unlit with nothing left to shade them.
TEST_F(GltfHardening, MaterialsUnlitIsAccepted) {
  const Scene s = loadGltf(scenetest::asset("UnlitTest/UnlitTest.glb"));
  ASSERT_EQ(s.materials.size(), 2u);
  for (const Material& m : s.materials) {
    EXPECT_TRUE(m.unlit) << m.name;
    EXPECT_EQ(m.metallicFactor, 0.0f);
    EXPECT_TRUE(m.emits());
    EXPECT_TRUE(m.nonDefaultReflectance());
  }
}

// ------------------------------------------------------------ from memory

TEST_F(GltfHardening, FromMemoryMatchesTheFileLoader) {
  TriangleGltf t;
  t.writeGltf(path("tri.gltf"));
  t.writeGlb(path("tri.glb"));
  for (const char* name : {"tri.gltf", "tri.glb"}) {
    SCOPED_TRACE(name);
    const std::vector<uint8_t> bytes = scenetest::readBytes(path(name));
    const Scene fromFile = loadGltf(path(name));
    const Scene fromMemory = loadGltfFromMemory(bytes.data(), bytes.size(), "memory", dir_.string());
    ASSERT_EQ(fromMemory.meshes.size(), 1u);
    EXPECT_EQ(fromMemory.meshes[0].positions, fromFile.meshes[0].positions);
    EXPECT_EQ(fromMemory.meshes[0].indices, fromFile.meshes[0].indices);
    EXPECT_EQ(fromMemory.source, "memory");
  }
  // .glb is recognised by its magic, not by a name.
  const std::vector<uint8_t> glb = scenetest::readBytes(path("tri.glb"));
  EXPECT_EQ(loadGltfFromMemory(glb.data(), glb.size(), "named.gltf", "").triangleCount(), 1u);
}

TEST_F(GltfHardening, FromMemoryResolvesUrisAgainstBaseDir) {
  TriangleGltf t;
  t.writeGltfExternal(path("ext.gltf"), path("ext.bin"), "ext.bin");
  const std::vector<uint8_t> bytes = scenetest::readBytes(path("ext.gltf"));
  EXPECT_EQ(loadGltfFromMemory(bytes.data(), bytes.size(), "ext", dir_.string()).triangleCount(), 1u);
  std::filesystem::create_directories(dir_ / "elsewhere");
  try {
    loadGltfFromMemory(bytes.data(), bytes.size(), "ext-elsewhere", path("elsewhere"));
    ADD_FAILURE() << "expected a RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("ext-elsewhere: ", 0), 0u) << msg;
    expectContains(msg, path("elsewhere") + "/ext.bin : no such file");
  }
}

TEST_F(GltfHardening, FromMemoryRefusesEmptyAndGarbage) {
  const unsigned char junk[] = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, 1, 2, 3};
  const std::vector<std::pair<const unsigned char*, size_t>> inputs = {
      {nullptr, 0}, {junk, 0}, {junk, 3}, {junk, sizeof junk}, {junk + 4, sizeof junk - 4}};
  for (const auto& [data, size] : inputs) {
    SCOPED_TRACE(size);
    try {
      loadGltfFromMemory(data, size, "junk-name", "");
      ADD_FAILURE() << "expected a RuntimeError";
    } catch (const RuntimeError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("junk-name: ", 0), 0u) << e.what();
    }
  }
}
