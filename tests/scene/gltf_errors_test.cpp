// Broken glTF files throw rgraph::RuntimeError naming the file and the problem,
// and never crash or read out of bounds.
#include <gtest/gtest.h>

#include <string>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::asset;
using scenetest::TriangleGltf;

namespace {

// Loads `path`, expecting a RuntimeError whose message names the file and contains `needle`.
void expectLoadError(const std::string& path, const std::string& needle = "") {
  try {
    Scene s = loadGltf(path);
    ADD_FAILURE() << path << ": expected a RuntimeError, loaded " << s.primitives.size() << " primitives";
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << "message does not name the file: " << msg;
    if (!needle.empty()) {
      EXPECT_NE(msg.find(needle), std::string::npos) << "message lacks '" << needle << "': " << msg;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": expected RuntimeError, got another exception: " << e.what();
  }
}

class GltfErrors : public scenetest::TempDirTest {};

}  // namespace

TEST_F(GltfErrors, TheValidTriangleLoads) {
  // The baseline every other test in this file breaks.
  TriangleGltf t;
  t.writeGltf(path("ok.gltf"));
  t.writeGlb(path("ok.glb"));
  t.writeGltfExternal(path("ext.gltf"), path("ext.bin"), "ext.bin");
  for (const char* f : {"ok.gltf", "ok.glb", "ext.gltf"}) {
    Scene s = loadGltf(path(f));
    EXPECT_EQ(s.triangleCount(), 1u) << f;
    EXPECT_EQ(s.materials.size(), 1u) << f;  // the default material
  }
}

TEST_F(GltfErrors, MissingFile) { expectLoadError(path("does_not_exist.gltf"), "not found"); }

TEST_F(GltfErrors, TruncatedGlb) {
  const std::vector<uint8_t> box = scenetest::readBytes(asset("Box/Box.glb"));
  ASSERT_GT(box.size(), 100u);
  for (size_t len : {size_t(0), size_t(3), size_t(11), size_t(12), size_t(19), size_t(20), size_t(100), box.size() / 2,
                     box.size() - 100, box.size() - 4, box.size() - 1}) {
    const std::string p = path("truncated_" + std::to_string(len) + ".glb");
    scenetest::writeBytes(p, box.data(), len);
    SCOPED_TRACE(len);
    expectLoadError(p);
  }
}

TEST_F(GltfErrors, GarbageBytes) {
  std::vector<uint8_t> junk(4096);
  uint32_t x = 12345;
  for (uint8_t& b : junk) {
    x = x * 1664525u + 1013904223u;
    b = uint8_t(x >> 24);
  }
  for (const char* name : {"garbage.gltf", "garbage.glb"}) {
    scenetest::writeBytes(path(name), junk.data(), junk.size());
    expectLoadError(path(name));
  }
  // A GLB magic followed by garbage.
  junk[0] = 'g', junk[1] = 'l', junk[2] = 'T', junk[3] = 'F';
  scenetest::writeBytes(path("magic.glb"), junk.data(), junk.size());
  expectLoadError(path("magic.glb"));
}

TEST_F(GltfErrors, BadJson) {
  scenetest::writeText(path("bad.gltf"), "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {\"mesh\": 0 ");
  expectLoadError(path("bad.gltf"));
  scenetest::writeText(path("empty.gltf"), "");
  expectLoadError(path("empty.gltf"));
}

TEST_F(GltfErrors, MissingTextureFile) {
  TriangleGltf t;
  t.doc["images"] = nlohmann::json::parse(R"([{"uri": "missing_texture.png"}])");
  t.doc["textures"] = nlohmann::json::parse(R"([{"source": 0}])");
  t.doc["materials"] = nlohmann::json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  t.doc["meshes"][0]["primitives"][0]["material"] = 0;
  t.writeGltf(path("missing_texture.gltf"));
  expectLoadError(path("missing_texture.gltf"), "missing_texture.png");
}

TEST_F(GltfErrors, UndecodableTexture) {
  TriangleGltf t;
  t.doc["images"] = nlohmann::json::parse(R"([{"uri": "not_an_image.png"}])");
  t.doc["textures"] = nlohmann::json::parse(R"([{"source": 0}])");
  t.doc["materials"] = nlohmann::json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  t.writeGltf(path("bad_texture.gltf"));
  scenetest::writeText(path("not_an_image.png"), "this is not a PNG");
  expectLoadError(path("bad_texture.gltf"));
}

TEST_F(GltfErrors, MissingExternalBuffer) {
  TriangleGltf t;
  t.writeGltfExternal(path("ext.gltf"), path("ext.bin"), "ext.bin");
  std::filesystem::remove(path("ext.bin"));
  expectLoadError(path("ext.gltf"));
}

TEST_F(GltfErrors, ExternalBufferTooSmall) {
  TriangleGltf t;
  t.writeGltfExternal(path("short.gltf"), path("short.bin"), "short.bin");
  scenetest::writeBytes(path("short.bin"), t.bin.data(), 20);  // byteLength says 44
  expectLoadError(path("short.gltf"));
}

TEST_F(GltfErrors, AccessorCountExceedsBuffer) {
  TriangleGltf t;
  t.doc["accessors"][0]["count"] = 100;
  t.writeGltf(path("count.gltf"));
  expectLoadError(path("count.gltf"), "accessor 0");
  t.writeGlb(path("count.glb"));
  expectLoadError(path("count.glb"), "accessor 0");
}

TEST_F(GltfErrors, HugeAccessorCount) {
  TriangleGltf t;
  t.doc["accessors"][0]["count"] = 4000000000ull;
  t.writeGltf(path("huge.gltf"));
  expectLoadError(path("huge.gltf"));
}

TEST_F(GltfErrors, AccessorOffsetBeyondBufferView) {
  TriangleGltf t;
  t.doc["accessors"][0]["byteOffset"] = 40;
  t.writeGltf(path("offset.gltf"));
  expectLoadError(path("offset.gltf"), "accessor 0");
}

TEST_F(GltfErrors, StrideTooLarge) {
  TriangleGltf t;
  t.doc["bufferViews"][0]["byteStride"] = 24;  // 3 elements at stride 24 need 60 bytes, the view has 36
  t.writeGltf(path("stride.gltf"));
  expectLoadError(path("stride.gltf"), "accessor 0");
}

TEST_F(GltfErrors, BufferViewExceedsBuffer) {
  TriangleGltf t;
  t.doc["bufferViews"][1]["byteLength"] = 600;
  t.writeGltf(path("view.gltf"));
  expectLoadError(path("view.gltf"), "buffer view 1");
}

TEST_F(GltfErrors, IndexOutOfRange) {
  TriangleGltf t;
  uint16_t bad = 7;
  std::memcpy(t.bin.data() + 36 + 2, &bad, 2);  // second index = 7, only 3 vertices
  t.writeGltf(path("index.gltf"));
  expectLoadError(path("index.gltf"), "index 7");
  t.writeGlb(path("index.glb"));
  expectLoadError(path("index.glb"), "index 7");
}

TEST_F(GltfErrors, AccessorIndexOutOfRange) {
  TriangleGltf t;
  t.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 9;
  t.writeGltf(path("attr.gltf"));
  expectLoadError(path("attr.gltf"), "accessor 9");
}

TEST_F(GltfErrors, AttributeCountMismatch) {
  TriangleGltf t;
  // NORMAL with 2 elements where POSITION has 3 (reuses the position bytes).
  t.doc["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
  t.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
  t.writeGltf(path("mismatch.gltf"));
  expectLoadError(path("mismatch.gltf"), "NORMAL");
}

TEST_F(GltfErrors, WrongAccessorType) {
  TriangleGltf t;
  t.doc["accessors"][0]["type"] = "VEC2";
  t.writeGltf(path("type.gltf"));
  expectLoadError(path("type.gltf"), "POSITION");
}

TEST_F(GltfErrors, FloatIndices) {
  TriangleGltf t;
  t.doc["accessors"][1]["componentType"] = 5126;
  t.doc["accessors"][1]["count"] = 1;
  t.writeGltf(path("floatidx.gltf"));
  expectLoadError(path("floatidx.gltf"));
}

TEST_F(GltfErrors, BadReferences) {
  {
    TriangleGltf t;
    t.doc["nodes"][0]["mesh"] = 3;
    t.writeGltf(path("mesh.gltf"));
    expectLoadError(path("mesh.gltf"), "mesh 3");
  }
  {
    TriangleGltf t;
    t.doc["meshes"][0]["primitives"][0]["material"] = 2;
    t.writeGltf(path("material.gltf"));
    expectLoadError(path("material.gltf"), "material 2");
  }
  {
    TriangleGltf t;
    t.doc["materials"] = nlohmann::json::parse(R"([{"normalTexture": {"index": 4}}])");
    t.writeGltf(path("texture.gltf"));
    expectLoadError(path("texture.gltf"), "texture 4");
  }
  {
    TriangleGltf t;
    t.doc["scenes"][0]["nodes"] = {5};
    t.writeGltf(path("node.gltf"));
    expectLoadError(path("node.gltf"), "node 5");
  }
}

TEST_F(GltfErrors, NodeCycle) {
  TriangleGltf t;
  t.doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])");
  t.writeGltf(path("cycle.gltf"));
  expectLoadError(path("cycle.gltf"));
}

TEST_F(GltfErrors, BadNodeTransform) {
  TriangleGltf t;
  t.doc["nodes"][0]["rotation"] = {0, 0, 1};
  t.writeGltf(path("rotation.gltf"));
  expectLoadError(path("rotation.gltf"), "rotation");
}

TEST_F(GltfErrors, GlbImageBufferViewOutOfRange) {
  TriangleGltf t;
  const std::vector<uint8_t> png = scenetest::tinyPng();
  const size_t at = t.bin.size();
  scenetest::append(t.bin, png);
  scenetest::pad4(t.bin);
  t.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", png.size() + 5000}});
  t.doc["images"] = nlohmann::json::parse(R"([{"bufferView": 2, "mimeType": "image/png"}])");
  t.doc["textures"] = nlohmann::json::parse(R"([{"source": 0}])");
  t.doc["materials"] = nlohmann::json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  t.writeGlb(path("image_view.glb"));
  expectLoadError(path("image_view.glb"), "buffer view 2");
}

// Every truncation of a real .glb and many single-byte corruptions either load
// or throw RuntimeError (run under ASan to also catch out-of-bounds reads).
TEST_F(GltfErrors, FuzzedBoxNeverCrashes) {
  const std::vector<uint8_t> box = scenetest::readBytes(asset("Box/Box.glb"));
  const std::string p = path("fuzz.glb");
  int loaded = 0, rejected = 0;
  auto attempt = [&](const std::vector<uint8_t>& bytes) {
    scenetest::writeBytes(p, bytes.data(), bytes.size());
    try {
      Scene s = loadGltf(p);
      s.validate();
      ++loaded;
    } catch (const RuntimeError&) {
      ++rejected;
    }
  };
  for (size_t len = 0; len < box.size(); len += 7) attempt(std::vector<uint8_t>(box.begin(), box.begin() + long(len)));
  uint32_t x = 99;
  for (int i = 0; i < 400; ++i) {
    std::vector<uint8_t> b = box;
    for (int k = 0; k < 1 + i % 4; ++k) {
      x = x * 1664525u + 1013904223u;
      const size_t at = (x >> 8) % b.size();
      x = x * 1664525u + 1013904223u;
      b[at] = uint8_t(x >> 24);
    }
    attempt(b);
  }
  EXPECT_GT(rejected, 0);
  EXPECT_GT(loaded, 0);
}

// The same for the JSON side: corrupt numbers in the triangle document.
TEST_F(GltfErrors, FuzzedJsonNumbersNeverCrash) {
  const std::vector<std::string> pointers = {"/accessors/0/count", "/accessors/0/byteOffset", "/accessors/1/count",
                                             "/accessors/1/componentType", "/accessors/0/bufferView", "/bufferViews/0/byteOffset",
                                             "/bufferViews/0/byteLength", "/bufferViews/1/byteOffset", "/bufferViews/1/buffer",
                                             "/meshes/0/primitives/0/indices", "/meshes/0/primitives/0/attributes/POSITION",
                                             "/nodes/0/mesh", "/scenes/0/nodes/0", "/buffers/0/byteLength"};
  const std::vector<long long> values = {-1, 0, 1, 2, 3, 4, 5, 35, 36, 37, 43, 44, 45, 5121, 5125, 65535, 2147483647, 4294967295LL};
  for (const std::string& ptr : pointers) {
    for (long long v : values) {
      TriangleGltf t;
      t.doc[nlohmann::json::json_pointer(ptr)] = v;
      const std::string p = path("fuzz.gltf");
      t.writeGltf(p);
      try {
        Scene s = loadGltf(p);
        s.validate();
      } catch (const RuntimeError&) {
      }
    }
  }
  SUCCEED();
}
