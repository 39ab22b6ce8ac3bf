#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "rgraph/error.h"
#include "rgraph/image.h"

using namespace rgraph;

TEST(Image, WritesAPng) {
  auto path = std::filesystem::temp_directory_path() / ("rgraph_image_test_" + std::to_string(::getpid()) + ".png");
  std::vector<uint8_t> rgba(4 * 3 * 4, 0x80);
  writePng(path.string(), 4, 3, rgba);
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in.good());
  char sig[8] = {};
  in.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  in.close();
  std::filesystem::remove(path);
}

TEST(Image, WrongSizeThrows) {
  std::vector<uint8_t> rgba(10);
  EXPECT_THROW(writePng("/tmp/never.png", 4, 4, rgba), RuntimeError);
}

TEST(Image, UnwritablePathIsNamed) {
  std::vector<uint8_t> rgba(4 * 4 * 4);
  try {
    writePng("/nonexistent_dir/sub/out.png", 4, 4, rgba);
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/sub/out.png"), std::string::npos) << e.what();
  }
}
