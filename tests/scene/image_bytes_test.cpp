// Images are checked before stb_image decodes them (core/src/scene/image_bytes.h):
// glTF images must be PNG or JPEG, environments Radiance .hdr, PNG or JPEG, and
// a JPEG whose Huffman table declares more than 256 codes is refused unread
// (the Debian stb_image writes past its tables on one: fuzz_gltf found it).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using nlohmann::json;
using scenetest::TriangleGltf;

namespace {

using Writer = int (*)(stbi_write_func*, void*, int, int, int, const void*);

void appendBytes(void* ctx, void* data, int size) {
  auto* v = static_cast<std::vector<uint8_t>*>(ctx);
  v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
}

// An 8 x 8 gradient, red rising left to right, as a baseline JPEG.
std::vector<uint8_t> gradientJpeg() {
  std::vector<uint8_t> px;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) px.insert(px.end(), {uint8_t(x * 32), 64, 128});
  std::vector<uint8_t> out;
  EXPECT_TRUE(stbi_write_jpg_to_func(appendBytes, &out, 8, 8, 3, px.data(), 95));
  return out;
}

std::vector<uint8_t> tinyTga() {
  const uint8_t px[4] = {1, 2, 3, 255};
  std::vector<uint8_t> out;
  EXPECT_TRUE(stbi_write_tga_to_func(appendBytes, &out, 1, 1, 4, px));
  return out;
}

// `jpeg` with its first Huffman table's longest code lengths counted up until
// the table declares `codes` codes, a value byte inserted for each new code and
// the segment's length grown to match: a well-formed segment but for the count.
std::vector<uint8_t> withHuffmanCodes(std::vector<uint8_t> jpeg, int codes) {
  for (size_t i = 0; i + 21 < jpeg.size(); ++i) {
    if (jpeg[i] != 0xFF || jpeg[i + 1] != 0xC4) continue;
    uint8_t* counts = &jpeg[i + 5];  // FF C4, length (2), class/id, counts[16]
    int sum = 0;
    for (int k = 0; k < 16; ++k) sum += counts[k];
    const int before = sum;
    for (int k = 15; k >= 0 && sum < codes; --k) {
      const int add = std::min(255 - int(counts[k]), codes - sum);
      counts[k] = uint8_t(counts[k] + add);
      sum += add;
    }
    const size_t length = (size_t(jpeg[i + 2]) << 8 | jpeg[i + 3]) + size_t(sum - before);
    EXPECT_LE(length, 0xFFFFu);
    jpeg[i + 2] = uint8_t(length >> 8);
    jpeg[i + 3] = uint8_t(length);
    jpeg.insert(jpeg.begin() + std::ptrdiff_t(i + 21 + size_t(before)), size_t(sum - before), uint8_t(0));
    return jpeg;
  }
  ADD_FAILURE() << "no DHT segment";
  return jpeg;
}

class ImageBytes : public scenetest::TempDirTest {
 protected:
  // The triangle with a base colour texture whose image is `bytes` as a data URI.
  std::string loadTextured(const std::vector<uint8_t>& bytes, const std::string& mime, Scene* out = nullptr) {
    TriangleGltf t;
    t.doc["images"] = {{{"uri", "data:" + mime + ";base64," + scenetest::base64(bytes)}}};
    t.doc["textures"] = {{{"source", 0}}};
    t.doc["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
    t.doc["meshes"][0]["primitives"][0]["material"] = 0;
    t.writeGltf(path("t.gltf"));
    try {
      Scene s = loadGltf(path("t.gltf"));
      if (out) *out = std::move(s);
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "";
  }
  std::string environmentError(const std::vector<uint8_t>& bytes, const std::string& name) {
    scenetest::writeText(path(name), std::string(bytes.begin(), bytes.end()));
    try {
      environmentFromSpec(path(name));
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "";
  }
};

}  // namespace

TEST_F(ImageBytes, BaselineJpegLoads) {
  Scene s;
  ASSERT_EQ(loadTextured(gradientJpeg(), "image/jpeg", &s), "");
  ASSERT_EQ(s.images.size(), 1u);
  const ImageData& img = s.images[0];
  ASSERT_EQ(img.width, 8);
  ASSERT_EQ(img.height, 8);
  // Red rises left to right in row 4; JPEG keeps it within a few steps.
  const uint8_t* row = &img.rgba[4 * 8 * 4];
  EXPECT_NEAR(row[0], 0, 12);
  EXPECT_NEAR(row[7 * 4], 224, 12);
  EXPECT_NEAR(row[3 * 4 + 1], 64, 12);
}

TEST_F(ImageBytes, JpegWithTooManyHuffmanCodesIsRefused) {
  // 256 codes is the most a table holds: still handed to the decoder (which
  // refuses the code lengths itself), 257 is refused before it.
  const std::string at256 = loadTextured(withHuffmanCodes(gradientJpeg(), 256), "image/jpeg");
  EXPECT_EQ(at256.find("declares"), std::string::npos) << at256;
  const std::string msg = loadTextured(withHuffmanCodes(gradientJpeg(), 4000), "image/jpeg");
  EXPECT_NE(msg.find("corrupt JPEG: a Huffman table declares 4000 codes (at most 256)"), std::string::npos) << msg;
  EXPECT_NE(msg.find(path("t.gltf")), std::string::npos) << msg;
}

TEST_F(ImageBytes, OnlyPngAndJpegInGltf) {
  const std::string msg = loadTextured(tinyTga(), "image/png");
  EXPECT_NE(msg.find("cannot decode (not a PNG or JPEG image)"), std::string::npos) << msg;
  EXPECT_EQ(loadTextured(scenetest::tinyPng(), "image/png"), "");
}

TEST_F(ImageBytes, EnvironmentsAreCheckedToo) {
  std::string msg = environmentError(withHuffmanCodes(gradientJpeg(), 300), "bad.jpg");
  EXPECT_NE(msg.find("bad.jpg: cannot read the environment image (corrupt JPEG: a Huffman table declares 300"),
            std::string::npos) << msg;
  msg = environmentError(tinyTga(), "sky.tga");
  EXPECT_NE(msg.find("sky.tga: cannot read the environment image (not a Radiance .hdr, PNG or JPEG image)"),
            std::string::npos) << msg;
  // A JPEG environment is read (as linear radiance after stb's 2.2 gamma).
  EXPECT_EQ(environmentError(gradientJpeg(), "ok.jpg"), "");
  // A header claiming more pixels than the limit is refused before decoding.
  const std::string huge = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 20000\n";
  msg = environmentError(std::vector<uint8_t>(huge.begin(), huge.end()), "huge.hdr");
  EXPECT_NE(msg.find("huge.hdr: the environment image is 20000x2 (at most 16384 on a side)"), std::string::npos) << msg;
}
