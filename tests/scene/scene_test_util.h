// Helpers shared by the scene tests: asset paths, a per-test temp dir, and
// builders for small glTF documents (JSON .gltf with embedded or external
// buffers, and .glb).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <stb_image_write.h>
#include <unistd.h>

namespace scenetest {

inline std::string asset(const std::string& rel) { return std::string(RGRAPH_ASSETS_DIR) + "/gltf/" + rel; }

inline std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

inline void writeBytes(const std::string& path, const void* data, size_t size) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(static_cast<const char*>(data), std::streamsize(size));
}

inline void writeText(const std::string& path, const std::string& text) { writeBytes(path, text.data(), text.size()); }

// Counts non-overlapping occurrences of `needle` in `text` (a warning in a log, say).
inline size_t countOf(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++n;
  return n;
}

// Collects what spdlog prints while it lives (warnings the loaders give).
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(out_);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("capture", sink));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
  std::shared_ptr<spdlog::logger> previous_;
};

// A fresh directory per test under the system temp dir; removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("rgraph_scene_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

inline std::string base64(const std::vector<uint8_t>& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8) | in[i + 2];
    out += t[v >> 18];
    out += t[(v >> 12) & 63];
    out += t[(v >> 6) & 63];
    out += t[v & 63];
  }
  if (i + 1 == in.size()) {
    uint32_t v = uint32_t(in[i]) << 16;
    out += t[v >> 18];
    out += t[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8);
    out += t[v >> 18];
    out += t[(v >> 12) & 63];
    out += t[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

template <class T>
void append(std::vector<uint8_t>& buf, const std::vector<T>& values) {
  const size_t at = buf.size();
  buf.resize(at + values.size() * sizeof(T));
  std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(T));
}

inline void pad4(std::vector<uint8_t>& buf) {
  while (buf.size() % 4) buf.push_back(0);
}

// One triangle in the z = 0 plane, CCW seen from +Z:
// buffer = 3 x vec3 positions (36 bytes) + 3 uint16 indices (6 bytes) + 2 padding.
// accessor 0: POSITION, accessor 1: indices. Tests mutate the JSON to break it.
struct TriangleGltf {
  nlohmann::json doc;
  std::vector<uint8_t> bin;

  TriangleGltf() {
    append(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    append(bin, std::vector<uint16_t>{0, 1, 2});
    pad4(bin);
    doc = nlohmann::json::parse(R"({
      "asset": {"version": "2.0"},
      "scene": 0,
      "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
        {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
      ],
      "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 36},
        {"buffer": 0, "byteOffset": 36, "byteLength": 6}
      ],
      "buffers": [{"byteLength": 44}]
    })");
  }

  // .gltf with the buffer embedded as a data URI.
  void writeGltf(const std::string& path) {
    nlohmann::json d = doc;
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
    d["buffers"][0]["byteLength"] = bin.size();
    writeText(path, d.dump(2));
  }

  // .gltf with an external .bin next to it (binName relative).
  void writeGltfExternal(const std::string& path, const std::string& binPath, const std::string& binName) {
    nlohmann::json d = doc;
    d["buffers"][0]["uri"] = binName;
    d["buffers"][0]["byteLength"] = bin.size();
    writeText(path, d.dump(2));
    writeBytes(binPath, bin.data(), bin.size());
  }

  // The JSON of the .glb form (the buffer is the BIN chunk).
  std::string glbJson() const {
    nlohmann::json d = doc;
    d["buffers"][0].erase("uri");
    d["buffers"][0]["byteLength"] = bin.size();
    return d.dump();
  }

  // .glb with the buffer as the BIN chunk.
  void writeGlb(const std::string& path) {
    const std::vector<uint8_t> out = makeGlb(glbJson(), bin);
    writeBytes(path, out.data(), out.size());
  }

  // A .glb from JSON text and BIN chunk bytes (both padded here).
  static std::vector<uint8_t> makeGlb(std::string js, std::vector<uint8_t> b) {
    while (js.size() % 4) js += ' ';
    pad4(b);
    std::vector<uint8_t> out = {'g', 'l', 'T', 'F'};
    auto u32 = [&](uint32_t v) { append(out, std::vector<uint32_t>{v}); };
    const uint32_t total = uint32_t(12 + 8 + js.size() + 8 + b.size());
    u32(2);
    u32(total);
    u32(uint32_t(js.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), js.begin(), js.end());
    u32(uint32_t(b.size()));
    u32(0x004E4942);
    out.insert(out.end(), b.begin(), b.end());
    return out;
  }
};

// A 2x2 RGBA PNG: red, green / blue, white.
inline std::vector<uint8_t> tinyPng() {
  const uint8_t px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  std::vector<uint8_t> out;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<uint8_t>*>(ctx);
        v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
      },
      &out, 2, 2, 4, px, 8);
  return out;
}

}  // namespace scenetest
