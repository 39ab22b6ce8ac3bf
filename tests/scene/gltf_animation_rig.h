// A small animated, skinned and morphed glTF built in memory for the
// animation tests: every accessor in its own buffer view of one embedded
// buffer. The rig: node 0 draws a triangle (mesh 0) skinned by skin 0, whose
// joints are node 1 (a root) and node 2 (its child at (0,0,10)); mesh 0 has
// one morph target (POSITION delta) with default weight 0.25. Tests add
// animations and edit the JSON to break it.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rgraph/scene.h"
#include "scene_test_util.h"

namespace animtest {

constexpr int kFloat = 5126, kU8 = 5121, kU16 = 5123;

struct GltfBuilder {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
    "accessors": [], "bufferViews": [], "buffers": [{"byteLength": 0}]})");
  std::vector<uint8_t> bin;

  // Appends `values` as one accessor of `count` elements; returns its index.
  template <class T>
  int accessor(const std::vector<T>& values, int componentType, const char* type, size_t count,
               bool normalized = false) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t at = bin.size();
    bin.resize(at + values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bin.data() + at, values.data(), values.size() * sizeof(T));
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", values.size() * sizeof(T)}});
    nlohmann::json a = {{"bufferView", doc["bufferViews"].size() - 1},
                        {"componentType", componentType},
                        {"count", count},
                        {"type", type}};
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const char* type, size_t count) { return accessor(v, kFloat, type, count); }

  // One animation with one sampler and one channel; returns its index.
  int animate(int node, const std::string& path, const std::string& interpolation, const std::vector<float>& times,
              const std::vector<float>& values, const char* valueType, size_t valueCount) {
    const int in = floats(times, "SCALAR", times.size());
    const int out = floats(values, valueType, valueCount);
    doc["animations"].push_back({{"samplers", {{{"input", in}, {"output", out}, {"interpolation", interpolation}}}},
                                 {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}}}});
    return int(doc["animations"].size()) - 1;
  }

  std::string text() const {
    nlohmann::json d = doc;
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + scenetest::base64(bin);
    d["buffers"][0]["byteLength"] = bin.size();
    return d.dump(1);
  }
  rgraph::Scene load() const {
    const std::string t = text();
    return rgraph::loadGltfFromMemory(reinterpret_cast<const unsigned char*>(t.data()), t.size(), "anim.gltf", "");
  }
};

// The rig described above; accessors 0 POSITION, 1 indices, 2 JOINTS_0,
// 3 WEIGHTS_0, 4 the target's POSITION delta, 5 inverse bind matrices.
// Vertex 0 follows joint 0, vertex 1 joint 1, vertex 2 half each.
inline GltfBuilder rig() {
  GltfBuilder b;
  b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  b.accessor(std::vector<uint16_t>{0, 1, 2}, kU16, "SCALAR", 3);
  b.accessor(std::vector<uint8_t>{0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0}, kU8, "VEC4", 3);
  b.floats({1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0}, "VEC4", 3);
  b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  std::vector<float> ibm;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 16; ++i) ibm.push_back(i % 5 == 0 ? 1.0f : 0.0f);
  ibm[16 + 14] = -10.0f;  // joint 1's inverse bind: T(0,0,-10)
  b.floats(ibm, "MAT4", 2);
  b.doc["meshes"].push_back(
      nlohmann::json::parse(R"({"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3},
      "indices": 1, "targets": [{"POSITION": 4}]}], "weights": [0.25]})"));
  b.doc["nodes"] = nlohmann::json::parse(R"([{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [0, 0, 10]}])");
  b.doc["scenes"][0]["nodes"] = {0, 1};
  b.doc["skins"] = nlohmann::json::parse(R"([{"joints": [1, 2], "inverseBindMatrices": 5}])");
  return b;
}

}  // namespace animtest
