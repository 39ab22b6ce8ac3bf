// Sub-pixel jitter (rgraph/jitter.h): the Halton(2,3) values and the pixel offsets a pipeline's frames get.
#include "rgraph/jitter.h"

#include <gtest/gtest.h>

using namespace rgraph;

TEST(Jitter, HaltonBase2And3KnownValues) {
  const float base2[8] = {1 / 2.f, 1 / 4.f, 3 / 4.f, 1 / 8.f, 5 / 8.f, 3 / 8.f, 7 / 8.f, 1 / 16.f};
  const float base3[8] = {1 / 3.f, 2 / 3.f, 1 / 9.f, 4 / 9.f, 7 / 9.f, 2 / 9.f, 5 / 9.f, 8 / 9.f};
  for (uint32_t i = 1; i <= 8; ++i) {
    EXPECT_NEAR(halton(i, 2), base2[i - 1], 1e-6f) << "index " << i;
    EXPECT_NEAR(halton(i, 3), base3[i - 1], 1e-6f) << "index " << i;
  }
}

TEST(Jitter, PixelsCycleThroughThePhases) {
  for (uint32_t phases : {8u, 16u}) {
    for (uint64_t frame = 0; frame < 2 * phases; ++frame) {
      const glm::vec2 j = jitterPixels(frame, phases);
      const uint32_t k = static_cast<uint32_t>(frame % phases) + 1;
      EXPECT_NEAR(j.x, halton(k, 2) - 0.5f, 1e-6f);
      EXPECT_NEAR(j.y, halton(k, 3) - 0.5f, 1e-6f);
      EXPECT_GT(j.x, -0.5f);
      EXPECT_LT(j.x, 0.5f);
      EXPECT_GT(j.y, -0.5f);
      EXPECT_LT(j.y, 0.5f);
      EXPECT_EQ(j, jitterPixels(frame + phases, phases)) << "period " << phases;
    }
  }
  // Frame 0 of 8 phases: (1/2 - 1/2, 1/3 - 1/2).
  EXPECT_NEAR(jitterPixels(0, 8).x, 0.0f, 1e-6f);
  EXPECT_NEAR(jitterPixels(0, 8).y, -1.0f / 6.0f, 1e-6f);
  // The 8 phases are distinct (each frame samples somewhere new).
  for (uint64_t a = 0; a < 8; ++a)
    for (uint64_t b = a + 1; b < 8; ++b) EXPECT_NE(jitterPixels(a, 8), jitterPixels(b, 8));
  // No phases: no jitter.
  EXPECT_EQ(jitterPixels(5, 0), glm::vec2(0.0f));
}
