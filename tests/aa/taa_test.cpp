// The taa plugin through pipelines/deferred-taa.json: what its history does
// on events that must reset it (camera cut, resize), on bad values in it
// (NaN/Inf), and its pass checks. Where a test compares against "the frame
// without history" it turns the pipeline's jitter off (jitterPhases = 0), so
// that a fresh executor's first frame is that frame exactly.
#include <GL/glcorearb.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>

#include "aa/aa_util.h"
#include "rgraph/scene.h"

using namespace rgraph;
using namespace rgraph::aatest;

namespace {

constexpr Extent kSize{128, 128};

class Taa : public rtest::RenderTest {};

PipelineConfig taaWithoutJitter() {
  PipelineConfig cfg = shippedPipeline("deferred-taa.json");
  EXPECT_EQ(cfg.jitterPhases, 8u) << "deferred-taa.json must jitter";
  cfg.jitterPhases = 0;
  return cfg;
}

// The LearnOpenGL scene from the side. Its black background matters: a
// history cleared to zero is then inside the neighbourhood of every edge
// against it, so a pass that blended a reset history would show there.
Camera sideCamera() {
  Camera c = makeLearnOpenGLScene().camera;
  c.position = {3.0f, 1.5f, 4.0f};
  c.target = {0.0f, -0.5f, 0.0f};
  return c;
}

size_t nonFinite(const std::vector<float>& v) {
  size_t n = 0;
  for (float f : v) n += !std::isfinite(f);
  return n;
}

}  // namespace

TEST_F(Taa, FirstFrameIsThePlainFrame) {
  // No history yet: the output is this frame's image, exactly default.json's
  // (the same passes before taa) when nothing is jittered.
  const Scene scene = makeLearnOpenGLScene();
  Frames taa(taaWithoutJitter(), scene, kSize, *shaders);
  const Image first = taa.next();
  const Image plain = rtest::render(shippedPipeline("default.json"), scene, kSize, *shaders);
  EXPECT_GT(rtest::coverage(first, {0, 0, 0}), 0.2) << rtest::saveImage(first, "taa-first");
  const rtest::ImageDiff d = rtest::compareImages(first, plain, 0);
  EXPECT_EQ(d.maxDiff, 0) << d.describe();
}

TEST_F(Taa, CameraCutResetsHistory) {
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig cfg = taaWithoutJitter();
  // The frame without history: default.json (taa's inputs, unjittered) from the side camera.
  Frames plain(shippedPipeline("default.json"), scene, kSize, *shaders);
  plain.exec().setCamera(sideCamera());
  const Image expected = plain.next();

  // Six frames from the front, then the side camera with a cut: the same frame.
  Frames cut(cfg, scene, kSize, *shaders);
  for (int i = 0; i < 6; ++i) cut.next();
  cut.exec().setCamera(sideCamera());
  cut.exec().cameraCut();
  const Image afterCut = cut.next();
  const rtest::ImageDiff d = rtest::compareImages(afterCut, expected, 0);
  std::printf("[ measure  ] first frame after a cut vs the frame without history: %s\n", d.describe().c_str());
  EXPECT_EQ(d.maxDiff, 0) << d.describe() << " " << rtest::saveImage(afterCut, "taa-after-cut");

  // The same switch without the cut blends the front view's history in: the
  // smear the cut prevents (proves the comparison above can fail).
  Frames smear(cfg, scene, kSize, *shaders);
  for (int i = 0; i < 6; ++i) smear.next();
  smear.exec().setCamera(sideCamera());
  const Image noCut = smear.next();
  const rtest::ImageDiff s = rtest::compareImages(noCut, expected, 2);
  std::printf("[ measure  ] the same switch without a cut: %s\n", s.describe().c_str());
  EXPECT_GE(s.maxDiff, 16) << "switching cameras without a cut left no trace: the test cannot see a smear";
}

TEST_F(Taa, ResizeResetsHistory) {
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig cfg = taaWithoutJitter();
  const Extent small{96, 80};
  const Image expected = rtest::render(shippedPipeline("default.json"), scene, small, *shaders);  // no history

  Frames resized(cfg, scene, kSize, *shaders);
  for (int i = 0; i < 5; ++i) resized.next();
  resized.exec().resize(small);
  const Image after = resized.next();
  ASSERT_EQ(after.extent, small);
  const rtest::ImageDiff d = rtest::compareImages(after, expected, 0);
  std::printf("[ measure  ] first frame after a resize vs the frame without history: %s\n", d.describe().c_str());
  EXPECT_EQ(d.maxDiff, 0) << d.describe() << " " << rtest::saveImage(after, "taa-after-resize");
}

TEST_F(Taa, NanAndInfInHistoryAreGoneTheNextFrame) {
  // Three runs of the same frames: untouched, poisoned after frame 6, and cut
  // before frame 7 (that frame without history, at the same jitter phase).
  const Scene scene = makeLearnOpenGLScene();
  const PipelineConfig cfg = shippedPipeline("deferred-taa.json");
  Frames control(cfg, scene, kSize, *shaders), poisoned(cfg, scene, kSize, *shaders), cut(cfg, scene, kSize, *shaders);
  for (int i = 0; i < 6; ++i) {
    control.next();
    poisoned.next();
    cut.next();
  }
  // A 24x24 block of NaN, +Inf and -Inf in the history the next frame reads
  // (GL rows 52..75: rows 52..75 from the top too, the size being 128).
  const uint32_t history = poisoned.exec().textureOf("taaHistory");
  ASSERT_NE(history, 0u);
  const float values[3] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity()};
  std::vector<float> block(24 * 24 * 4);
  for (size_t i = 0; i < block.size(); ++i) block[i] = values[(i / 4 + i) % 3];
  glTextureSubImage2D(history, 0, 52, 52, 24, 24, GL_RGBA, GL_FLOAT, block.data());
  ASSERT_GT(nonFinite(poisoned.exec().readTextureRGBA32F("taaHistory")), 24u * 24u) << "the injection did not land";

  const Image clean = control.next();
  const Image out = poisoned.next();
  cut.exec().cameraCut();
  const Image noHistory = cut.next();
  EXPECT_EQ(nonFinite(poisoned.exec().readTextureRGBA32F("taaResolved")), 0u)
      << "non-finite values in the resolved frame";
  // Inside the block (2 pixels in: bilinear taps there touch only poison)
  // the history is dropped: exactly the frame without history. Outside it
  // (2 pixels clear) nothing changed: exactly the control run.
  Mask inside(static_cast<size_t>(kSize.width) * kSize.height, false), poison = inside;
  for (int row = 52; row < 76; ++row)
    for (int x = 52; x < 76; ++x) {
      poison[static_cast<size_t>(row) * kSize.width + x] = true;
      inside[static_cast<size_t>(row) * kSize.width + x] = row >= 54 && row < 74 && x >= 54 && x < 74;
    }
  const Mask outside = awayFrom(poison, kSize, 2);
  const Error in = measure(out, noHistory, &inside), outE = measure(out, clean, &outside);
  const Error vsControl = measure(out, clean, &inside);
  std::printf(
      "[ measure  ] after NaN/Inf injection: block vs the no-history frame %s; vs control %s; "
      "outside vs control %s\n",
      in.describe().c_str(), vsControl.describe().c_str(), outE.describe().c_str());
  EXPECT_EQ(in.maxAbs, 0) << in.describe() << " " << rtest::saveImage(out, "taa-after-nan");
  EXPECT_EQ(outE.maxAbs, 0) << outE.describe();
  // And nothing non-finite is copied into the next history.
  poisoned.next();
  EXPECT_EQ(nonFinite(poisoned.exec().readTextureRGBA32F("taaHistory")), 0u);
}

TEST_F(Taa, MismatchedSizesAreErrorsAtTheBinding) {
  // velocity at half size: the taa check names the slot and both sizes.
  std::string text;
  {
    std::ifstream in(rtest::repoPath("pipelines/deferred-taa.json"));
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string from = R"("gVelocity":    { "format": "rg16f",   "size": "output")";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), R"("gVelocity":    { "format": "rg16f",   "size": { "scale": 0.5 })");
  const std::string all = checkErrors(text, "taa-half-velocity.json", Extent{64, 64});
  // The geometry pass refuses it too (its targets differ in size); the taa
  // check must be among the errors, at its velocity binding.
  EXPECT_NE(all.find("/inputs/velocity: taa pass 'taa': 'velocity' (32x32) and 'output' (64x64)"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("taa-half-velocity.json:"), std::string::npos) << all;
}

TEST_F(Taa, HistoryThatIsNotItsOwnOutputIsAnErrorAtTheBinding) {
  // Bound to an ordinary texture the resolve would never accumulate; bound to
  // another resource's history it would blend a stranger's image.
  std::string text;
  {
    std::ifstream in(rtest::repoPath("pipelines/deferred-taa.json"));
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string binding = R"("history": "taaHistory")";
  ASSERT_NE(text.find(binding), std::string::npos);
  std::string plain = text;
  plain.replace(plain.find(binding), binding.size(), R"("history": "hdr_forward")");
  const std::string notHistory = checkErrors(plain, "taa-plain-history.json", Extent{64, 64});
  EXPECT_NE(notHistory.find("/inputs/history: taa pass 'taa': 'hdr_forward' is not a history resource; declare one "
                            "with \"history_of\": \"taaResolved\""),
            std::string::npos)
      << notHistory;

  std::string other = text;
  const std::string decl = R"("taaHistory":   { "history_of": "taaResolved")";
  ASSERT_NE(other.find(decl), std::string::npos);
  other.replace(other.find(decl), decl.size(), R"("taaHistory":   { "history_of": "output")");
  // The output is presented, never kept: the graph refuses that history, so
  // point it at the forward HDR image instead.
  other.replace(other.find(R"("history_of": "output")"), 22, R"("history_of": "hdr")");
  const std::string stranger = checkErrors(other, "taa-other-history.json", Extent{64, 64});
  EXPECT_NE(stranger.find("'taaHistory' holds the history of 'hdr', not of this pass's output 'taaResolved'"),
            std::string::npos)
      << stranger;
}
