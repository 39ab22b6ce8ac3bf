// The fxaa plugin: synthetic images through an fxaa-only pipeline (the input
// an imported texture the test fills), then pipelines/deferred-fxaa.json on a
// scene. Flat regions must come out bit-exact; an aliased staircase must come
// out closer to its exact pixel coverage.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "aa/aa_util.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::aatest;

namespace {

constexpr Extent kSize{128, 128};

const char* kFxaaOnly = R"({
  "version": 1, "plugins": ["fxaa"],
  "resources": { "src": { "format": "rgba8", "imported": true }, "output": { "format": "rgba8" } },
  "passes": [ { "name": "fxaa", "type": "fxaa", "inputs": { "input": "src" }, "outputs": { "output": "output" } } ],
  "output": "output"
})";

class Fxaa : public rtest::RenderTest {
 protected:
  // `input` (rows top-down) through the fxaa pass; the imported texture's own
  // filter is `ownFilter` (GL's default magnification filter is linear).
  Image filter(const Image& input, GLenum ownFilter = GL_LINEAR) {
    const PipelineConfig cfg = loadPipelineTextOrThrow(kFxaaOnly, "fxaa-only.json");
    gl::Texture src = gl::createTexture(GL_TEXTURE_2D);
    const GLsizei w = static_cast<GLsizei>(input.extent.width), h = static_cast<GLsizei>(input.extent.height);
    glTextureStorage2D(src.id(), 1, GL_RGBA8, w, h);
    for (GLsizei row = 0; row < h; ++row)  // GL rows go bottom-up
      glTextureSubImage2D(src.id(), 0, 0, h - 1 - row, w, 1, GL_RGBA, GL_UNSIGNED_BYTE, input.at(0, row));
    glTextureParameteri(src.id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(ownFilter));
    glTextureParameteri(src.id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(ownFilter));
    Executor exec(cfg, processRegistry(), *shaders);
    exec.importTexture("src", src.id());
    exec.resize(input.extent);
    exec.renderFrame();
    Image out;
    out.extent = exec.outputExtent();
    out.rgba = exec.readOutputRGBA8();
    return out;
  }
};

Image makeImage(Extent e, const std::function<glm::ivec3(int x, int row)>& f) {
  Image img;
  img.extent = e;
  img.rgba.resize(static_cast<size_t>(e.width) * e.height * 4);
  for (int row = 0; row < static_cast<int>(e.height); ++row)
    for (int x = 0; x < static_cast<int>(e.width); ++x) {
      const glm::ivec3 c = f(x, row);
      uint8_t* p = &img.rgba[(static_cast<size_t>(row) * e.width + x) * 4];
      p[0] = static_cast<uint8_t>(c.r), p[1] = static_cast<uint8_t>(c.g), p[2] = static_cast<uint8_t>(c.b), p[3] = 255;
    }
  return img;
}

// A shallow edge: white below the line row = 40 + 0.17 x, black above.
// Coverage of a pixel = the share of its area below the line (16x16 samples).
constexpr double kSlope = 0.17, kOffset = 40.0;
double coverage(int x, int row) {
  int in = 0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) in += (row + (j + 0.5) / 16.0) > kOffset + kSlope * (x + (i + 0.5) / 16.0);
  return in / 256.0;
}

}  // namespace

TEST_F(Fxaa, FlatAndBlackImagesAreUnchanged) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> noise(-2, 2);  // below the contrast threshold (0.0312 ~ 8 levels)
  const std::vector<std::pair<std::string, Image>> cases = {
      {"black", makeImage(kSize, [](int, int) { return glm::ivec3(0); })},
      {"grey", makeImage(kSize, [](int, int) { return glm::ivec3(128, 128, 128); })},
      {"orange", makeImage(kSize, [](int, int) { return glm::ivec3(250, 120, 10); })},
      {"grey-noise", makeImage(kSize, [&](int, int) { return glm::ivec3(128 + noise(rng), 128 + noise(rng), 128); })},
  };
  for (const auto& [name, img] : cases) {
    const Image out = filter(img);
    const rtest::ImageDiff d = rtest::compareImages(out, img, 0);
    std::printf("[ measure  ] fxaa on %s: %s\n", name.c_str(), d.describe().c_str());
    EXPECT_EQ(d.maxDiff, 0) << name << ": " << d.describe() << " " << rtest::saveImage(out, "fxaa-" + name);
  }
}

// The input slot declares its sampler (bilinear, clamped): a caller's
// texture set to nearest filtering is filtered as the pass's taps need, so
// the result is the same as from a linearly filtered one. Without the
// declaration the taps between texels would snap to one texel.
TEST_F(Fxaa, TheInputsDeclaredSamplerOverridesTheTexturesOwnFilter) {
  const Image aliased = makeImage(kSize, [](int x, int row) { return glm::ivec3(coverage(x, row) >= 0.5 ? 255 : 0); });
  const Image linear = filter(aliased, GL_LINEAR);
  const Image nearest = filter(aliased, GL_NEAREST);
  ASSERT_GT(rtest::compareImages(linear, aliased, 0).maxDiff, 64) << "fxaa left the staircase alone";
  const rtest::ImageDiff d = rtest::compareImages(nearest, linear, 0);
  EXPECT_EQ(d.maxDiff, 0) << d.describe();
}

TEST_F(Fxaa, StaircaseEdgeMovesTowardsItsCoverage) {
  const Image aliased = makeImage(kSize, [](int x, int row) {
    return glm::ivec3(coverage(x, row) >= 0.5 ? 255 : 0);  // what the rasteriser does: pixel centre in or out
  });
  const Image out = filter(aliased);
  // Edge pixels: partly covered. Error of each image against exact coverage there.
  double errIn = 0.0, errOut = 0.0;
  int edgePixels = 0, intermediate = 0;
  for (int row = 0; row < static_cast<int>(kSize.height); ++row)
    for (int x = 0; x < static_cast<int>(kSize.width); ++x) {
      const double c = coverage(x, row) * 255.0;
      if (c <= 0.0 || c >= 255.0) continue;
      ++edgePixels;
      errIn += std::abs(aliased.at(x, row)[0] - c);
      errOut += std::abs(out.at(x, row)[0] - c);
      if (out.at(x, row)[0] >= 16 && out.at(x, row)[0] <= 239) ++intermediate;
    }
  errIn /= edgePixels;
  errOut /= edgePixels;
  std::printf(
      "[ measure  ] staircase: %d edge pixels, mean |error| vs coverage %.1f -> %.1f levels, "
      "%d with intermediate values (none before)\n",
      edgePixels, errIn, errOut, intermediate);
  EXPECT_LE(errOut, 0.6 * errIn) << rtest::saveImage(out, "fxaa-staircase");
  EXPECT_GE(intermediate, edgePixels / 2) << "the edge profile is still a step";

  // Away from the edge (2 pixels from any partly covered pixel) nothing moves.
  Mask edge(static_cast<size_t>(kSize.width) * kSize.height, false);
  for (int row = 0; row < static_cast<int>(kSize.height); ++row)
    for (int x = 0; x < static_cast<int>(kSize.width); ++x) {
      const double c = coverage(x, row);
      edge[static_cast<size_t>(row) * kSize.width + x] = c > 0.0 && c < 1.0;
    }
  const Mask flat = awayFrom(edge, kSize, 2);
  const Error e = measure(out, aliased, &flat);
  EXPECT_GT(e.pixels, kSize.width * kSize.height / 2);
  EXPECT_EQ(e.maxAbs, 0) << "fxaa changed flat pixels: " << e.describe();
}

// A wire thinner than a pixel in front of a fence: a white line 0.6 px
// thick, centre row = 40.3 + 0.02 x, over grey posts 3 px wide every 24 px
// on black. Sampled at pixel centres the wire is a 1-px dash in one row, a
// gap, then a dash in the next row; its exact coverage hardly reaches the
// rows either side of a dash. Those neighbours see a step towards the dash,
// but there is no step edge between them to place: a blend that treats it
// as one (its search stopping where the wire crosses a post) smears the wire
// into them. They must stay about as close to the exact image as they were,
// and the wire as a whole must come closer to it.
TEST_F(Fxaa, ThinLineIsNotSmearedIntoItsNeighbours) {
  auto onPost = [](int x) { return x % 24 < 3; };
  auto inWire = [](double x, double y) { return std::abs(y - (40.3 + 0.02 * x)) < 0.3; };
  auto exact = [&](int x, int row) {  // 16x16 samples; the posts fill whole pixels
    int in = 0;
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) in += inWire(x + (i + 0.5) / 16.0, row + (j + 0.5) / 16.0);
    const double c = in / 256.0;
    return c * 255.0 + (1.0 - c) * (onPost(x) ? 128.0 : 0.0);
  };
  const Image aliased = makeImage(kSize, [&](int x, int row) {
    return glm::ivec3(inWire(x + 0.5, row + 0.5) ? 255 : onPost(x) ? 128 : 0);
  });
  const Image out = filter(aliased);
  auto wireLit = [&](int x, int row) { return aliased.at(x, row)[0] == 255; };
  double nbIn = 0.0, nbOut = 0.0, wireIn = 0.0, wireOut = 0.0;
  int neighbours = 0, wirePixels = 0;
  for (int row = 1; row + 1 < static_cast<int>(kSize.height); ++row)
    for (int x = 0; x < static_cast<int>(kSize.width); ++x) {
      const double want = exact(x, row);
      const double errIn = std::abs(aliased.at(x, row)[0] - want), errOut = std::abs(out.at(x, row)[0] - want);
      if (wireLit(x, row) || std::abs(want - aliased.at(x, row)[0]) > 1.0) {  // the wire, sampled or not
        ++wirePixels;
        wireIn += errIn;
        wireOut += errOut;
      }
      if (!wireLit(x, row) && (wireLit(x, row - 1) || wireLit(x, row + 1))) {  // above or below a dash
        ++neighbours;
        nbIn += errIn;
        nbOut += errOut;
      }
    }
  std::printf(
      "[ measure  ] thin wire: %d neighbours of its dashes, mean |error| vs exact %.1f -> %.1f levels; "
      "%d wire pixels, %.1f -> %.1f levels\n",
      neighbours, nbIn / neighbours, nbOut / neighbours, wirePixels, wireIn / wirePixels, wireOut / wirePixels);
  ASSERT_GT(neighbours, static_cast<int>(kSize.width));  // above and below most dash pixels
  // Up to ~13 levels each: the sub-pixel term (a dash pixel's 3x3 low-pass)
  // moves its neighbours by 1/20 of the step; the step-edge blend would move
  // them by up to half of it.
  EXPECT_LE(nbOut, nbIn + 16.0 * neighbours) << "the wire was smeared into its neighbours "
                                             << rtest::saveImage(out, "fxaa-thin-wire");
  EXPECT_LE(wireOut, 0.7 * wireIn) << rtest::saveImage(out, "fxaa-thin-wire");
}

TEST_F(Fxaa, SizeMismatchIsAnErrorAtTheBinding) {
  std::string text = kFxaaOnly;
  text.replace(text.find(R"("output": { "format": "rgba8" })"), 31,
               R"("output": { "format": "rgba8", "size": { "scale": 0.5 } })");
  const std::string msg = checkErrors(text, "half.json", Extent{64, 64});
  ASSERT_FALSE(msg.empty()) << "no error for an output half the input's size";
  EXPECT_NE(msg.find("half.json:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fxaa pass 'fxaa'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(32x32)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(64x64)"), std::string::npos) << msg;
}

class FxaaScenes : public Fxaa, public ::testing::WithParamInterface<const char*> {};

TEST_P(FxaaScenes, DeferredPipelineKeepsFlatRegionsAndSmoothsEdges) {
  const Scene scene = loadSceneAny(GetParam());
  const PipelineConfig fxaa = shippedPipeline("deferred-fxaa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  const Extent size{192, 192};
  Image ldr;
  const Image out = rtest::render(fxaa, scene, size, *shaders, [&](Executor& exec) {
    std::vector<float> f = exec.readTextureRGBA32F("ldr");
    ldr.extent = size;
    ldr.rgba.resize(f.size());
    for (size_t i = 0; i < f.size(); ++i) ldr.rgba[i] = static_cast<uint8_t>(std::lround(f[i] * 255.0f));
  });
  const Image plain = rtest::render(none, scene, size, *shaders);
  // The tone-mapped image fxaa reads is default.json's frame.
  EXPECT_EQ(rtest::compareImages(ldr, plain, 0).maxDiff, 0);
  EXPECT_GT(rtest::coverage(out, {0, 0, 0}), 0.2) << rtest::saveImage(out, "deferred-fxaa");

  // Pixels whose 3x3 block varies by at most 4 levels per channel (flat
  // surfaces, smooth shading, faint texture: below the contrast threshold of
  // ~8 levels): bit-exact. A blur would move those with a gradient.
  Mask uniform(static_cast<size_t>(size.width) * size.height, false);
  size_t sloped = 0;  // of them, pixels not all one colour: where a blur would show
  for (int row = 1; row + 1 < static_cast<int>(size.height); ++row)
    for (int x = 1; x + 1 < static_cast<int>(size.width); ++x) {
      glm::ivec3 lo(255), hi(0);
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          lo = glm::min(lo, ldr.rgb(x + i, row + j));
          hi = glm::max(hi, ldr.rgb(x + i, row + j));
        }
      const int spread = std::max({hi.r - lo.r, hi.g - lo.g, hi.b - lo.b});
      uniform[static_cast<size_t>(row) * size.width + x] = spread <= 4;
      sloped += spread > 0 && spread <= 4;
    }
  const Error flat = measure(out, ldr, &uniform);
  std::printf("[ measure  ] deferred-fxaa on nearly flat 3x3 blocks (%zu not uniform): %s\n", sloped,
              flat.describe().c_str());
  EXPECT_GT(flat.pixels, 1000u);
  EXPECT_GT(sloped, 200u);
  EXPECT_EQ(flat.maxAbs, 0) << flat.describe();

  // Edges against the 16-sample reference of the plain pipeline.
  const Image ref = supersampled(none, scene, size, 4, *shaders);
  const Mask edges = edgeMask(ref, 24);
  const Error before = measure(plain, ref, &edges), after = measure(out, ref, &edges);
  std::printf("[ measure  ] edges (%zu px) vs 4x4 supersampled: none %s; fxaa %s\n", count(edges),
              before.describe().c_str(), after.describe().c_str());
  EXPECT_GE(after.psnr - before.psnr, 1.0) << rtest::saveImage(out, "deferred-fxaa");
}

INSTANTIATE_TEST_SUITE_P(Scenes, FxaaScenes, ::testing::Values("learnopengl:overview", "thin"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           return std::string(info.param == std::string("thin") ? "Thin" : "LearnOpenGLOverview");
                         });
