// TAA stability over frames (issue 13), each measured and asserted: a trail
// left by a moving object that stops, a background revealed by a moving
// camera, flicker of sub-pixel geometry under a slow camera, and a converged
// static frame against a supersampled reference. "none" is default.json (no
// jitter, no history): the frame TAA must end up agreeing with away from
// edges, and beating on edges.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <glm/gtc/matrix_transform.hpp>

#include "aa/aa_util.h"
#include "render/test_scenes.h"
#include "rgraph/pipeline_load.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"

using namespace rgraph;
using namespace rgraph::aatest;

namespace {

constexpr Extent kSize{128, 128};

class TaaStability : public rtest::RenderTest {};

glm::mat4 cubeAt(float x) { return rtest::translate({x, 0.0f, 0.0f}); }

// Mean over pixels of the temporal variance of luma (8-bit units^2).
double meanTemporalVariance(const std::vector<Image>& frames) {
  const size_t n = frames.front().rgba.size() / 4;
  double total = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0, s2 = 0.0;
    for (const Image& f : frames) {
      const double y = 0.299 * f.rgba[i * 4] + 0.587 * f.rgba[i * 4 + 1] + 0.114 * f.rgba[i * 4 + 2];
      s += y;
      s2 += y * y;
    }
    const double m = s / static_cast<double>(frames.size());
    total += s2 / static_cast<double>(frames.size()) - m * m;
  }
  return total / static_cast<double>(n);
}

}  // namespace

TEST_F(TaaStability, TaaGhostingTrailFadesAfterObjectStops) {
  Scene scene = makeStage();
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  // Where the cube was while it moved (x = -1.6 .. 0.2, 0.15 per frame).
  Scene empty = scene;
  empty.primitives[kCube].transform = cubeAt(100.0f);
  const Image background = rtest::render(none, empty, kSize, *shaders);
  Mask trail(static_cast<size_t>(kSize.width) * kSize.height, false);
  Frames taa(taaCfg, scene, kSize, *shaders);
  float x = -1.6f;
  for (int i = 0; i < 13; ++i, x += 0.15f) {
    scene.primitives[kCube].transform = cubeAt(x);
    taa.next();
    const Mask covered = differsFrom(rtest::render(none, scene, kSize, *shaders), background, 8);
    for (size_t p = 0; p < trail.size(); ++p) trail[p] = trail[p] || covered[p];
  }
  // It stops at x = 0.2: the trail is what it covered, 3 pixels clear of where it is now.
  scene.primitives[kCube].transform = cubeAt(0.2f);
  const Image still = rtest::render(none, scene, kSize, *shaders);
  const Mask here = differsFrom(still, background, 8);
  const Mask clear = awayFrom(here, kSize, 3);
  for (size_t p = 0; p < trail.size(); ++p) trail[p] = trail[p] && clear[p];
  ASSERT_GT(count(trail), 400u) << "the cube did not sweep a trail";

  // Error of the trail against the no-TAA frame, per frame after the stop.
  std::string series;
  Error last;
  for (int k = 0; k < 4; ++k) {
    const Image out = taa.next();
    last = measure(out, still, &trail);
    series += " " + std::to_string(last.maxAbs);
    if (k == 3) {
      EXPECT_LE(last.maxAbs, 4) << last.describe() << " " << rtest::saveImage(out, "taa-ghost");
    }
  }
  std::printf("[ measure  ] trail (%zu px) max error per frame after the stop:%s/255; last %s\n", count(trail),
              series.c_str(), last.describe().c_str());
}

TEST_F(TaaStability, TaaDisocclusionRevealedBackgroundConverges) {
  // The camera slides left past the cube (in front of the wall): the wall
  // that the cube uncovers each frame has no history of its own.
  const Scene scene = makeStage();
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  Frames taa(taaCfg, scene, kSize, *shaders);
  auto cameraAt = [&](int frame) {
    Camera c = scene.camera;
    const glm::vec3 shift{1.0f - 0.15f * static_cast<float>(frame), 0.0f, 0.0f};
    c.position += shift;
    c.target += shift;
    return c;
  };
  std::vector<Image> outs, refs;
  for (int f = 0; f < 14; ++f) {
    taa.exec().setCamera(cameraAt(f));
    outs.push_back(taa.next());
    Executor plain(none, processRegistry(), *shaders, &scene);
    plain.setCamera(cameraAt(f));
    plain.resize(kSize);
    plain.renderFrame();
    Image r;
    r.extent = kSize;
    r.rgba = plain.readOutputRGBA8();
    refs.push_back(std::move(r));
  }
  // Pixels uncovered at frame f: cube at f-1, wall at f, 2 pixels clear of
  // the cube's edges at f + 2 (when they are measured).
  const int kLag = 2;  // converged within 2 frames of being revealed
  Error worst;
  size_t revealed = 0;
  for (int f = 4; f + kLag < 14; ++f) {
    Mask m(static_cast<size_t>(kSize.width) * kSize.height, false);
    const Mask edgesLater = edgeMask(refs[f + kLag], 12);
    const Mask clearLater = awayFrom(edgesLater, kSize, 2);
    for (size_t p = 0; p < m.size(); ++p) {
      const uint8_t* before = &refs[f - 1].rgba[p * 4];
      const uint8_t* now = &refs[f].rgba[p * 4];
      const uint8_t* later = &refs[f + kLag].rgba[p * 4];
      const bool cubeBefore = before[0] > before[1] + 40;  // red
      const bool wallNow = std::abs(now[0] - now[1]) < 8, wallLater = std::abs(later[0] - later[1]) < 8;
      m[p] = cubeBefore && wallNow && wallLater && clearLater[p];
    }
    revealed += count(m);
    // Measured the frame it is revealed (already mostly right) and kLag later.
    const Error e = measure(outs[f + kLag], refs[f + kLag], &m);
    if (e.maxAbs >= worst.maxAbs) worst = e;
    const Error now = measure(outs[f], refs[f], &m);
    std::printf("[ measure  ] frame %d: %zu px revealed; error then max %d/255, %d frames later max %d/255\n", f,
                count(m), now.maxAbs, kLag, e.maxAbs);
  }
  ASSERT_GT(revealed, 100u) << "the camera move revealed nothing";
  EXPECT_LE(worst.maxAbs, 4) << worst.describe();
}

TEST_F(TaaStability, TaaThinGeometryFlickersLessUnderASlowCamera) {
  const Scene scene = makeThinScene();
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  Frames taa(taaCfg, scene, kSize, *shaders), plain(none, scene, kSize, *shaders);
  std::vector<Image> withTaa, without;
  for (int f = 0; f < 28; ++f) {
    Camera c = scene.camera;
    const glm::vec3 shift{0.003f * static_cast<float>(f), 0.0015f * static_cast<float>(f), 0.0f};  // ~0.1 px/frame
    c.position += shift;
    c.target += shift;
    taa.exec().setCamera(c);
    plain.exec().setCamera(c);
    Image a = taa.next(), b = plain.next();
    if (f >= 12) {  // TAA converged
      withTaa.push_back(std::move(a));
      without.push_back(std::move(b));
    }
  }
  const double vTaa = meanTemporalVariance(withTaa), vNone = meanTemporalVariance(without);
  std::printf("[ measure  ] thin scene, slow camera: mean temporal luma variance none %.2f, taa %.2f (x%.2f)\n", vNone,
              vTaa, vTaa / vNone);
  EXPECT_GT(vNone, 1.0) << "the thin scene does not flicker without TAA: the test measures nothing";
  EXPECT_LT(vTaa, 0.5 * vNone);
}

TEST_F(TaaStability, TaaConvergedStaticFrameIsCloserToSupersampledOnEdges) {
  const Scene scene = makeThinScene();
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  Frames taa(taaCfg, scene, kSize, *shaders);
  Image converged;
  for (int f = 0; f < 16; ++f) converged = taa.next();
  const Image plain = rtest::render(none, scene, kSize, *shaders);
  const Image ref = supersampled(none, scene, kSize, 4, *shaders);
  const Mask edges = edgeMask(ref, 24);
  const Error a = measure(plain, ref, &edges), b = measure(converged, ref, &edges);
  const Error wa = measure(plain, ref), wb = measure(converged, ref);
  std::printf(
      "[ measure  ] thin scene, %zu edge px vs 4x4 supersampled: none %s; taa %s (whole image %.2f -> %.2f dB)\n",
      count(edges), a.describe().c_str(), b.describe().c_str(), wa.psnr, wb.psnr);
  ASSERT_GT(count(edges), 300u);
  EXPECT_GE(b.psnr - a.psnr, 2.0) << rtest::saveImage(converged, "taa-converged");
}

TEST_F(TaaStability, TaaReprojectionFollowsAPanningCamera) {
  // Vertical bars 2-3 pixels wide, alternating colours, in front of the
  // wall; the camera pans ~2.3 pixels a frame. Every pixel's 3x3 holds both
  // colours, so the clip cannot tell a history fetched from the wrong place:
  // only the motion vectors keep the bars where they are. Measured against
  // the 16-sample reference of each frame's camera, per converged frame.
  Scene scene = makeStage();
  scene.primitives[kCube].transform = cubeAt(100.0f);  // out of the way
  const int bar = rtest::addMesh(scene, makeCube(0.5f));
  const int colours[2] = {rtest::addMaterial(scene, {0.9f, 0.8f, 0.1f, 1.0f}, 0.0f, 1.0f, 0.0f),
                          rtest::addMaterial(scene, {0.1f, 0.3f, 0.9f, 1.0f}, 0.0f, 1.0f, 0.0f)};
  for (int i = 0; i < 40; ++i)
    rtest::addDraw(
        scene, bar, colours[i % 2],
        glm::scale(rtest::translate({-4.0f + 0.2f * static_cast<float>(i), 0.0f, -1.5f}), {0.1f, 3.0f, 0.1f}));
  const Camera start = scene.camera;
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  Frames taa(taaCfg, scene, kSize, *shaders);
  double worstGain = 1e9, sumGain = 0.0;
  int measured = 0;
  for (int f = 0; f < 14; ++f) {
    const glm::vec3 shift{0.11f * static_cast<float>(f), 0.0f, 0.0f};
    scene.camera.position = start.position + shift;
    scene.camera.target = start.target + shift;
    const Image a = taa.next();  // the executor follows the scene's camera
    if (f < 8) continue;         // converged
    const Image b = rtest::render(none, scene, kSize, *shaders);
    const Image ref = supersampled(none, scene, kSize, 4, *shaders);
    const Error ea = measure(a, ref), eb = measure(b, ref);
    std::printf("[ measure  ] pan frame %d vs 4x4 supersampled: none %.2f dB, taa %.2f dB\n", f, eb.psnr, ea.psnr);
    worstGain = std::min(worstGain, ea.psnr - eb.psnr);
    sumGain += ea.psnr - eb.psnr;
    ++measured;
  }
  // Measured: +0.5 .. +2.3 dB per frame (mean +1.4); motion vectors ignored: -4.3 .. -5.8 dB.
  EXPECT_GE(worstGain, 0.0) << "TAA under camera motion is worse than the plain frame";
  EXPECT_GE(sumGain / measured, 1.0) << "TAA under camera motion does not beat the plain frame";
}

TEST_F(TaaStability, TaaOrbitKeepsForwardDrawnLightBoxesInPlace) {
  // The LearnOpenGL overview orbiting 1 degree a frame. Its light boxes are
  // drawn by the forward pass, which writes no motion vectors: the taa pass
  // reprojects them by depth and camera motion. Without that their history
  // stays put and smears (measured -5 dB against the plain frame on edges).
  Scene scene = loadSceneAny("learnopengl:overview");
  const Camera start = scene.camera;
  const Extent size{160, 90};
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  Frames taa(taaCfg, scene, size, *shaders);
  double worstGain = 1e9, sumGain = 0.0;
  int measured = 0;
  for (int f = 0; f < 14; ++f) {
    scene.camera = orbitCamera(start, 1.0f * static_cast<float>(f));
    const Image a = taa.next();
    if (f < 8) continue;  // converged
    const Image b = rtest::render(none, scene, size, *shaders);
    const Image ref = supersampled(none, scene, size, 4, *shaders);
    const Mask edges = edgeMask(ref, 24);
    const Error ea = measure(a, ref, &edges), eb = measure(b, ref, &edges);
    std::printf("[ measure  ] orbit frame %d, %zu edge px vs 4x4 supersampled: none %.2f dB, taa %.2f dB\n", f,
                ea.pixels, eb.psnr, ea.psnr);
    worstGain = std::min(worstGain, ea.psnr - eb.psnr);
    sumGain += ea.psnr - eb.psnr;
    ++measured;
  }
  // Measured +4.2 .. +5.3 dB (mean +4.8); +2.8 .. +4.5 (mean +3.8) with
  // current_filter 0 (moving pixels take the raw jittered sample), +0.6 ..
  // +1.6 before the light boxes' own depth test (velocity_depth), the
  // young-history running mean, the shorter history in motion and the linear
  // blend below luma 1.
  EXPECT_GE(worstGain, 3.5) << "TAA during the orbit gains too little over the plain frame on edges";
  EXPECT_GE(sumGain / measured, 4.3);
}

TEST_F(TaaStability, TaaForwardDrawnBoxInFrontOfGeometryMovesWithTheCamera) {
  // A light box (drawn by the forward pass, after the G-buffer, without
  // motion vectors) 1.5 units before a panning camera, in front of the wall:
  // it moves ~4 pixels a frame, the wall behind it ~1, whose motion
  // the velocity target holds there. With velocity_depth bound (the shipped
  // pipeline) the taa pass sees the box is nearer than the velocity's surface
  // and reprojects it with the camera; without it, the box's history is
  // fetched where the wall was. Both against each frame's 16-sample reference.
  Scene scene = makeStage();
  scene.primitives[kCube].transform = cubeAt(100.0f);  // out of the way
  scene.pointLights.push_back(rtest::pointLight({-0.2f, 0.1f, 3.5f}, {1.0f, 0.6f, 0.2f}, 0.5f));
  const Camera start = scene.camera;
  const PipelineConfig with = shippedPipeline("deferred-taa.json");
  std::ifstream in(rtest::repoPath("pipelines/deferred-taa.json"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string binding = ", \"velocity_depth\": \"gDepth\"";
  ASSERT_NE(text.find(binding), std::string::npos);
  text.erase(text.find(binding), binding.size());
  const std::string withoutPath =
      (std::filesystem::temp_directory_path() / ("taa-without-velocity-depth-" + std::to_string(::getpid()) + ".json"))
          .string();
  std::ofstream(withoutPath) << text;
  const PipelineConfig without = loadPipelineFileOrThrow(withoutPath);
  std::filesystem::remove(withoutPath);
  const PipelineConfig none = shippedPipeline("default.json");
  Frames a(with, scene, kSize, *shaders), b(without, scene, kSize, *shaders);
  double sumGain = 0.0;
  int measured = 0;
  for (int f = 0; f < 12; ++f) {
    const glm::vec3 shift{0.03f * static_cast<float>(f), 0.0f, 0.0f};
    scene.camera.position = start.position + shift;
    scene.camera.target = start.target + shift;
    const Image ia = a.next(), ib = b.next();
    if (f < 8) continue;
    const Image ref = supersampled(none, scene, kSize, 4, *shaders);
    const Error ea = measure(ia, ref), eb = measure(ib, ref);
    std::printf("[ measure  ] pan frame %d vs 4x4 supersampled: with velocity_depth %.2f dB, without %.2f dB\n", f,
                ea.psnr, eb.psnr);
    sumGain += std::min(ea.psnr, 100.0) - std::min(eb.psnr, 100.0);
    ++measured;
  }
  // Measured: -1.1 .. +10.1 dB per frame, mean +4.6 (the wall alone matches
  // the reference to ~50 dB, so the box's ghost is most of the error).
  EXPECT_GE(sumGain / measured, 1.0) << "the light box does not reproject with the camera";
}

TEST_F(TaaStability, TaaStillCameraConvergesEarlyAndKeepsBrightEdgesBright) {
  // The LearnOpenGL overview from a still camera: bright light boxes and lit
  // cubes on black. Two properties of the blend, each against the 16-sample
  // reference on edges:
  //  - after 4 frames: a young history is a running mean (1/2, 1/3, 1/4 of
  //    each new frame), not 0.9 of the first, aliased frame from the start;
  //  - after 24 frames: below luma 1 the blend is linear, as the reference's
  //    average of displayed values is; inverse-luma weights there weight
  //    every dark sample up and darken each edge between bright and dark.
  const Scene scene = loadSceneAny("learnopengl:overview");
  const Extent size{160, 90};
  const PipelineConfig taaCfg = shippedPipeline("deferred-taa.json");
  const PipelineConfig none = shippedPipeline("default.json");
  const Image ref = supersampled(none, scene, size, 4, *shaders);
  const Mask edges = edgeMask(ref, 24);
  const Error plain = measure(rtest::render(none, scene, size, *shaders), ref, &edges);
  Frames taa(taaCfg, scene, size, *shaders);
  Image early, late;
  for (int f = 0; f < 24; ++f) {
    const Image frame = taa.next();
    if (f == 3) early = frame;
    if (f == 23) late = frame;
  }
  const Error e4 = measure(early, ref, &edges), e24 = measure(late, ref, &edges);
  std::printf("[ measure  ] overview, %zu edge px vs 4x4 supersampled: none %.2f dB, taa frame 4 %.2f dB, frame 24 %.2f dB\n",
              count(edges), plain.psnr, e4.psnr, e24.psnr);
  // Measured (none 19.84 dB): frame 4 24.86 dB (+5.0; 23.53 dB, +3.7, with
  // the weight 0.9 from the first frame), frame 24 30.26 dB (+10.4; 27.11 dB,
  // +7.3, with inverse-luma weights below luma 1 too).
  EXPECT_GE(e4.psnr - plain.psnr, 4.5) << "4 frames in, the history is still mostly the first frame";
  EXPECT_GE(e24.psnr - plain.psnr, 9.0) << "the converged edges are off (darkened?)";
}
