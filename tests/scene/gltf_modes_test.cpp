// glTF primitive modes and compressed geometry: triangle strips and fans
// turned into triangle lists with the winding glTF gives them, points and
// lines skipped out loud, KHR_mesh_quantization attributes, and
// KHR_draco_mesh_compression refused by name (or its uncompressed fallback drawn).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::asset;
using scenetest::TriangleGltf;

namespace {

// The unnormalised face normal of triangle t (twice its area).
glm::vec3 faceNormal(const MeshData& m, size_t t) {
  const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
  return glm::cross(b - a, c - a);
}

// Total area of the mesh's triangles projected on z = 0, signed: positive when they face +Z.
float signedAreaZ(const MeshData& m) {
  float sum = 0.0f;
  for (size_t t = 0; t < m.triangleCount(); ++t) sum += 0.5f * faceNormal(m, t).z;
  return sum;
}

// A row of `n` vertices zig-zagging along +X in z = 0, (i/2, (i+1)%2, 0): as a
// strip every triangle faces +Z. With `fan`, a fan around the origin over a
// half circle instead (counter-clockwise seen from +Z). One primitive, mode
// `mode`, with uint16 indices 0..n-1 unless `indexed` is false.
TriangleGltf sequence(int mode, size_t n, bool indexed, bool fan) {
  TriangleGltf t;
  t.bin.clear();
  std::vector<float> pos;
  for (size_t i = 0; i < n; ++i) {
    if (fan) {
      const float a = i == 0 ? 0.0f : 3.14159265f * float(i - 1) / float(n - 2);
      const float r = i == 0 ? 0.0f : 1.0f;
      pos.insert(pos.end(), {r * std::cos(a), r * std::sin(a), 0.0f});
    } else {
      pos.insert(pos.end(), {float(i / 2), float((i + 1) % 2), 0.0f});
    }
  }
  scenetest::append(t.bin, pos);
  std::vector<uint16_t> idx;
  for (size_t i = 0; i < n; ++i) idx.push_back(uint16_t(i));
  scenetest::append(t.bin, idx);
  scenetest::pad4(t.bin);
  t.doc["accessors"][0]["count"] = n;
  t.doc["accessors"][0]["min"] = {-1, 0, 0};
  t.doc["accessors"][0]["max"] = {float(n), 1, 0};
  t.doc["accessors"][1]["count"] = n;
  t.doc["bufferViews"][0]["byteLength"] = 12 * n;
  t.doc["bufferViews"][1] = {{"buffer", 0}, {"byteOffset", 12 * n}, {"byteLength", 2 * n}};
  t.doc["meshes"][0]["primitives"][0]["mode"] = mode;
  if (!indexed) t.doc["meshes"][0]["primitives"][0].erase("indices");
  return t;
}

class GltfModes : public scenetest::TempDirTest {
 protected:
  Scene load(TriangleGltf& t, const std::string& name = "t.gltf") {
    t.writeGltf(path(name));
    return loadGltf(path(name));
  }
};

constexpr int kStrip = 5, kFan = 6;

}  // namespace

TEST_F(GltfModes, StripsBecomeTrianglesFacingOneWay) {
  for (bool indexed : {true, false}) {
    SCOPED_TRACE(indexed ? "indexed" : "not indexed");
    TriangleGltf t = sequence(kStrip, 6, indexed, false);
    Scene s = load(t);
    ASSERT_EQ(s.meshes.size(), 1u);
    const MeshData& m = s.meshes[0];
    ASSERT_EQ(m.triangleCount(), 4u);  // n - 2
    // Every second triangle's order is swapped: all face +Z like the first.
    for (size_t i = 0; i < 4; ++i) EXPECT_GT(faceNormal(m, i).z, 0.5f) << "triangle " << i;
    EXPECT_NEAR(signedAreaZ(m), 2.0f, 1e-6f);  // the 2 x 1 band, covered once
    for (const glm::vec3& nrm : m.normals) EXPECT_NEAR(nrm.z, 1.0f, 1e-6f);
  }
}

TEST_F(GltfModes, FansBecomeTrianglesFacingOneWay) {
  for (bool indexed : {true, false}) {
    SCOPED_TRACE(indexed ? "indexed" : "not indexed");
    TriangleGltf t = sequence(kFan, 6, indexed, true);
    Scene s = load(t);
    ASSERT_EQ(s.meshes.size(), 1u);
    const MeshData& m = s.meshes[0];
    ASSERT_EQ(m.triangleCount(), 4u);
    for (size_t i = 0; i < 4; ++i) EXPECT_GT(faceNormal(m, i).z, 0.1f) << "triangle " << i;
    for (const glm::vec3& nrm : m.normals) EXPECT_NEAR(nrm.z, 1.0f, 1e-6f);
  }
}

TEST_F(GltfModes, StripTrianglesRepeatingAVertexAreDropped) {
  TriangleGltf t = sequence(kStrip, 6, true, false);
  // 0 1 2 2 3 4 -> (0,1,2) (1,2,2)x (2,2,3)x (2,4,3): two zero-area triangles.
  const std::vector<uint16_t> idx = {0, 1, 2, 2, 3, 4};
  std::memcpy(t.bin.data() + 72, idx.data(), 12);
  Scene s = load(t);
  EXPECT_EQ(s.meshes[0].triangleCount(), 2u);
}

TEST_F(GltfModes, TooShortAStripIsSkippedWithAWarning) {
  TriangleGltf t = sequence(kStrip, 2, true, false);
  scenetest::LogCapture log;
  Scene s = load(t);
  EXPECT_TRUE(s.primitives.empty());
  EXPECT_EQ(scenetest::countOf(log.text(), "no triangles; skipped"), 1u) << log.text();
}

TEST_F(GltfModes, PointsAndLinesAreSkippedNamingTheMode) {
  TriangleGltf t;
  const json tri = t.doc["meshes"][0]["primitives"][0];
  for (int mode : {0, 1, 2, 3}) {
    json p = tri;
    p["mode"] = mode;
    t.doc["meshes"][0]["primitives"].push_back(p);
  }
  scenetest::LogCapture log;
  Scene s = load(t);
  EXPECT_EQ(s.primitives.size(), 1u);
  for (const char* name : {"(POINTS)", "(LINES)", "(LINE_LOOP)", "(LINE_STRIP)"})
    EXPECT_EQ(scenetest::countOf(log.text(), name), 1u) << name << "\n" << log.text();
  EXPECT_EQ(s.warnings.size(), 4u);
}

// The sample draws one hexagon per mode: POINTS, LINES, LINE_LOOP,
// LINE_STRIP, TRIANGLES (6 triangles), TRIANGLE_STRIP (6 indices: 4
// triangles), TRIANGLE_FAN (8 indices: 6 triangles), all in z = 0.
TEST(GltfModesSample, MeshPrimitiveModesStripAndFanMatchTheTriangles) {
  scenetest::LogCapture log;
  const Scene s = loadGltf(asset("MeshPrimitiveModes/MeshPrimitiveModes.gltf"));
  ASSERT_EQ(s.meshes.size(), 3u);  // the triangles, the strip, the fan
  EXPECT_EQ(s.meshes[0].triangleCount(), 6u);
  EXPECT_EQ(s.meshes[1].triangleCount(), 4u);
  EXPECT_EQ(s.meshes[2].triangleCount(), 6u);
  // Same hexagon, same side: the strip and the fan cover the TRIANGLES
  // primitive's area once each, every triangle facing +Z as its triangles do.
  const float hexagon = signedAreaZ(s.meshes[0]);
  EXPECT_NEAR(hexagon, 3.0f * 0.866f, 1e-4f);
  for (size_t k = 1; k < 3; ++k) {
    EXPECT_NEAR(signedAreaZ(s.meshes[k]), hexagon, 1e-5f) << "mesh " << k;
    for (size_t i = 0; i < s.meshes[k].triangleCount(); ++i) EXPECT_GT(faceNormal(s.meshes[k], i).z, 0.0f) << k << " " << i;
  }
  for (const char* name : {"(POINTS)", "(LINES)", "(LINE_LOOP)", "(LINE_STRIP)"})
    EXPECT_EQ(scenetest::countOf(log.text(), name), 1u) << name << "\n" << log.text();
}

// ------------------------------------------------------------ KHR_mesh_quantization

namespace {

// The triangle with its POSITION as `type` (5120 BYTE, 5121 UNSIGNED_BYTE,
// 5122 SHORT, 5123 UNSIGNED_SHORT), `normalized` or not, holding `values`
// (9 components), and a NORMAL accessor of `normalType` holding (0, 0, max)
// where max is the type's largest value; the file requires the extension.
TriangleGltf quantized(int type, bool normalized, const std::vector<int>& values, int normalType, bool normalNormalized) {
  TriangleGltf t;
  t.bin.clear();
  auto put = [&](int ct, const std::vector<int>& v) {
    const size_t at = t.bin.size();
    for (int x : v) {
      if (ct == 5120) scenetest::append(t.bin, std::vector<int8_t>{int8_t(x)});
      if (ct == 5121) scenetest::append(t.bin, std::vector<uint8_t>{uint8_t(x)});
      if (ct == 5122) scenetest::append(t.bin, std::vector<int16_t>{int16_t(x)});
      if (ct == 5123) scenetest::append(t.bin, std::vector<uint16_t>{uint16_t(x)});
    }
    // Each element padded to 4 bytes, as the specification requires for vertex attributes.
    const size_t comp = (ct == 5120 || ct == 5121) ? 1 : 2;
    std::vector<uint8_t> padded;
    for (size_t e = 0; e < 3; ++e) {
      for (size_t b = 0; b < 3 * comp; ++b) padded.push_back(t.bin[at + e * 3 * comp + b]);
      while (padded.size() % 4) padded.push_back(0);
    }
    t.bin.resize(at);
    t.bin.insert(t.bin.end(), padded.begin(), padded.end());
    return std::make_pair(at, padded.size());
  };
  const auto [posAt, posLen] = put(type, values);
  const int nmax = normalType == 5120 ? 127 : normalType == 5122 ? 32767 : 255;
  const auto [nrmAt, nrmLen] = put(normalType, {0, 0, nmax, 0, 0, nmax, 0, 0, nmax});
  const size_t idxAt = t.bin.size();
  scenetest::append(t.bin, std::vector<uint16_t>{0, 1, 2});
  scenetest::pad4(t.bin);
  const size_t stride = posLen / 3;
  t.doc["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", posAt}, {"byteLength", posLen}, {"byteStride", stride}},
                                      {{"buffer", 0}, {"byteOffset", idxAt}, {"byteLength", 6}},
                                      {{"buffer", 0}, {"byteOffset", nrmAt}, {"byteLength", nrmLen}, {"byteStride", nrmLen / 3}}});
  t.doc["accessors"][0] = {{"bufferView", 0}, {"componentType", type}, {"normalized", normalized}, {"count", 3}, {"type", "VEC3"}};
  t.doc["accessors"].push_back(
      {{"bufferView", 2}, {"componentType", normalType}, {"normalized", normalNormalized}, {"count", 3}, {"type", "VEC3"}});
  t.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
  t.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  t.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  return t;
}

}  // namespace

TEST_F(GltfModes, QuantizedPositionsDecodeToKnownValues) {
  struct Case {
    int type;
    bool normalized;
    std::vector<int> values;
    glm::vec3 second;  // what vertex 1 decodes to
  };
  const Case cases[] = {
      {5120, false, {0, 0, 0, -100, 0, 0, 0, 100, 0}, {-100, 0, 0}},
      {5120, true, {0, 0, 0, -127, 0, 0, 0, 127, 0}, {-1, 0, 0}},
      {5121, false, {0, 0, 0, 200, 0, 0, 0, 200, 0}, {200, 0, 0}},
      {5121, true, {0, 0, 0, 255, 0, 0, 0, 255, 0}, {1, 0, 0}},
      {5122, false, {0, 0, 0, -3000, 0, 0, 0, 3000, 0}, {-3000, 0, 0}},
      {5122, true, {0, 0, 0, 32767, 0, 0, 0, 32767, 0}, {1, 0, 0}},
      {5123, false, {0, 0, 0, 60000, 0, 0, 0, 60000, 0}, {60000, 0, 0}},
      {5123, true, {0, 0, 0, 65535, 0, 0, 0, 65535, 0}, {1, 0, 0}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("componentType " + std::to_string(c.type) + (c.normalized ? " normalized" : ""));
    TriangleGltf t = quantized(c.type, c.normalized, c.values, 5120, true);
    Scene s = load(t);
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].positions[1], c.second);
    EXPECT_EQ(s.meshes[0].normals[0], glm::vec3(0, 0, 1));
  }
  // A normalized SHORT normal.
  TriangleGltf t = quantized(5122, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}, 5122, true);
  EXPECT_EQ(load(t).meshes[0].normals[2], glm::vec3(0, 0, 1));
}

TEST_F(GltfModes, QuantizedCombinationsOutsideTheTableAreRefusedAtTheAttribute) {
  struct Case {
    int normalType;
    bool normalized;
    const char* says;
  };
  const Case cases[] = {
      {5120, false, "accessor 2 is BYTE (not normalized); NORMAL may be FLOAT, or normalized BYTE or SHORT"},
      {5122, false, "accessor 2 is SHORT (not normalized); NORMAL may be"},
      {5121, true, "accessor 2 is normalized UNSIGNED_BYTE; NORMAL may be"},
  };
  for (const Case& c : cases) {
    TriangleGltf t = quantized(5122, false, {0, 0, 0, 1, 0, 0, 0, 1, 0}, c.normalType, c.normalized);
    t.writeGltf(path("q.gltf"));
    try {
      loadGltf(path("q.gltf"));
      ADD_FAILURE() << "expected a refusal: " << c.says;
    } catch (const RuntimeError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("/meshes/0/primitives/0/attributes/NORMAL: "), std::string::npos) << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << what;
      EXPECT_NE(what.find("q.gltf:"), std::string::npos) << what;
    }
  }
}

// ------------------------------------------------------------ KHR_draco_mesh_compression

namespace {

// The triangle's primitive marked as Draco-compressed (the extension object
// pointing at buffer view 0, as a real file's compressed data would).
void addDraco(TriangleGltf& t) {
  t.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  t.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 0},
                                                                                   {"attributes", {{"POSITION", 0}}}};
}

}  // namespace

TEST_F(GltfModes, DracoRequiredIsRefusedByNameBeforeParsing) {
  TriangleGltf t;
  addDraco(t);
  t.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  // As Draco encoders write them: the accessors have no buffer view (tinygltf
  // alone says "accessor[1] invalid bufferView").
  t.doc["accessors"][0].erase("bufferView");
  t.doc["accessors"][1].erase("bufferView");
  t.writeGltf(path("draco.gltf"));
  try {
    loadGltf(path("draco.gltf"));
    ADD_FAILURE() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("draco.gltf:"), std::string::npos) << what;
    EXPECT_NE(what.find("/extensionsRequired/0: requires KHR_draco_mesh_compression"), std::string::npos) << what;
    EXPECT_EQ(what.find("invalid bufferView"), std::string::npos) << what;
  }
}

TEST_F(GltfModes, DracoUsedWithoutUncompressedDataIsRefusedAtThePrimitive) {
  TriangleGltf t;
  addDraco(t);
  t.doc["accessors"][1].erase("bufferView");  // the indices exist only compressed
  t.writeGltf(path("draco.gltf"));
  try {
    loadGltf(path("draco.gltf"));
    ADD_FAILURE() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression: the primitive is Draco-compressed"),
              std::string::npos)
        << what;
  }
}

TEST_F(GltfModes, DracoUsedWithUncompressedDataDrawsItAndWarnsOnce) {
  TriangleGltf t;
  addDraco(t);
  t.doc["meshes"][0]["primitives"].push_back(t.doc["meshes"][0]["primitives"][0]);  // two compressed primitives
  scenetest::LogCapture log;
  Scene s = load(t);
  EXPECT_EQ(s.primitives.size(), 2u);
  EXPECT_EQ(s.triangleCount(), 2u);
  EXPECT_EQ(scenetest::countOf(log.text(), "KHR_draco_mesh_compression ignored: the primitives' uncompressed accessors are drawn"), 1u)
      << log.text();
}
