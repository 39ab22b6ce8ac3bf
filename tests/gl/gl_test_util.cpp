#include "gl_test_util.h"

#include "rgraph/error.h"
#include "support/test_support.h"

namespace rgraph::test {

GlContext& glContext() { return testsupport::sharedGlContext(); }

void GlTest::SetUp() {
  try {
    glContext();
  } catch (const RuntimeError& e) {
    FAIL() << "no headless GL context: " << e.what();
  }
  shaders = std::make_unique<ShaderLibrary>();
  shaders->addSearchDirectory(std::string(RGRAPH_TEST_DATA_DIR) + "/gl/shaders");
  errorsAtStart = glContext().debugErrorCount();
}

void GlTest::TearDown() {
  shaders.reset();
  if (testsupport::hasSharedGlContext()) {
    EXPECT_EQ(glContext().debugErrorCount(), errorsAtStart) << "GL debug errors, last: " << glContext().lastDebugError();
  }
}

size_t gradientMismatches(const std::vector<uint8_t>& rgba, Extent e, std::string* first) {
  size_t bad = 0;
  if (rgba.size() != static_cast<size_t>(e.width) * e.height * 4) return static_cast<size_t>(-1);
  for (uint32_t row = 0; row < e.height; ++row) {
    uint32_t yGl = e.height - 1 - row;
    for (uint32_t x = 0; x < e.width; ++x) {
      auto want = gradientPixel(x, yGl);
      const uint8_t* got = &rgba[(static_cast<size_t>(row) * e.width + x) * 4];
      if (got[0] != want[0] || got[1] != want[1] || got[2] != want[2] || got[3] != want[3]) {
        if (bad == 0 && first)
          *first = "pixel (" + std::to_string(x) + "," + std::to_string(row) + ") = " + std::to_string(got[0]) + "," +
                   std::to_string(got[1]) + "," + std::to_string(got[2]) + "," + std::to_string(got[3]) +
                   ", expected " + std::to_string(want[0]) + "," + std::to_string(want[1]) + "," +
                   std::to_string(want[2]) + "," + std::to_string(want[3]);
        ++bad;
      }
    }
  }
  return bad;
}

::testing::AssertionResult outputIsGradient(const Executor& exec, Extent e) {
  std::string first;
  const size_t bad = gradientMismatches(exec.readOutputRGBA8(), e, &first);
  if (bad == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << bad << " pixels differ from gradient.frag's; " << first;
}

}  // namespace rgraph::test
