// `rgraph bench`, the post axis (bench_post.cpp): bloom as a full-size
// Gaussian ping-pong against bloom as a mip chain, and SSAO at full size
// against SSAO at half size with a depth-aware upsample, on
// pipelines/deferred-ssao-bloom.json (each variant made from it by changing
// only the effect measured) at 1920x1080: bloom on the default scene, SSAO on
// many-lights:32 (objects on a floor). Rows carry the axis name "post". Both
// bloom methods blur a full-size bright image (the chain with six levels);
// the shipped file blurs a half-size one with five.
//
//   time: the effect's passes (per-pass clock, glFinish after each) and the
//         whole frame, medians over timed frames; the methods of an effect
//         are rendered in turn, frame by frame;
//   bloom error: each method's blurred bright image (bloom_blur's dst)
//         against a wide-blur reference computed on the CPU from the same
//         bright image: the blur the method stands for, exactly and
//         shift-invariantly (bloomReference() below); relative RMS error and
//         PSNR (peak: the reference's maximum), on every 8th pixel of every
//         8th row;
//   ssao error: the half-size methods' ambient visibility (as the lighting
//         pass sees it) against the full-size method's, and the final images
//         against each other; half_bilinear is the half-size SSAO without the
//         depth-aware upsample (the lighting pass samples it bilinearly), to
//         show what the upsample buys.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph {
class ShaderLibrary;
}

namespace rgraph::cli::bench {

struct PostRow {
  std::string effect;  // bloom, ssao
  std::string method;  // bloom: gaussian, mip_chain; ssao: full, half, half_bilinear
  std::string scene;   // loadSceneAny spec
  Extent size{1920, 1080};
  std::vector<double> frameMs, effectMs;
  double spreadPx = 0.0;        // bloom: rms radius of the reference kernel (px)
  double relError = 0.0;        // bloom: relative RMS error against the reference; ssao: RMS of visibility
  double psnr = 0.0;            // dB: bloom against the reference; ssao: visibility against full size
  double imagePsnr = 0.0;       // ssao: final 8-bit image against the full-size method's
  uint64_t allocatedBytes = 0, naiveBytes = 0;
  std::string error;  // non-empty: the row failed
  bool ok() const { return error.empty(); }
};

struct PostPlan {
  Extent size{1920, 1080};
  int warm = 1, timedFrames = 3;
};
PostPlan postPlan(bool quick);
std::vector<PostRow> planPost(const PostPlan& plan);
// Renders every row; returns the number that failed.
size_t runPost(std::vector<PostRow>& rows, const PostPlan& plan, const std::string& pipelineDir,
               ShaderLibrary& shaders);
nlohmann::json postJson(const PostRow& r);
// "post_bloom" (chain speed-up >= 2, spread >= the Gaussian's) and "post_ssao" into checks.
void postChecks(const std::vector<PostRow>& rows, nlohmann::json& checks, std::vector<std::string>& summary);

}  // namespace rgraph::cli::bench
