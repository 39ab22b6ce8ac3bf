// `rgraph bench`, the shadows axis (bench_shadows.cpp): shadow filters (hard,
// pcf 3/5/7, pcss, evsm), map resolutions and sun cascades on
// pipelines/deferred-pbr-shadows.json and scenes/shadows.json, each variant
// made from the shipped file by changing only its shadow params; plus the
// same pipeline with shadows off ("none": what shadows cost). Rows carry the
// axis name "shadows".
//
//   time: the whole frame and the shadow_map passes (the per-pass clock),
//         medians over timed frames;
//   memory: the atlas's bytes (the depth array every map is a layer of);
//   error: the lighting pass's HDR image against the exact-visibility image,
//         both tone-mapped on the CPU with the pipeline's tonemap params and
//         stored as 8-bit sRGB: PSNR and the share of pixels off by more than
//         1/255 (compareImages, as the other axes).
//
// The exact-visibility image (ShadowReference): the lighting pass is linear
// in its lights, so the image with exact shadows is
//     base + sum over casting lights i of vis_i(pixel) * (L_i - D)
// where base is the scene with every casting light removed (ambient and the
// non-casting lights), L_i the scene with casting light i alone and no
// ambient, D the same with that light's intensity at 0 (the clear colour,
// whatever the lighting pass leaves where nothing was drawn), all with
// shadows off; vis_i is the ray caster's binary visibility
// (rgraph_visibility_oracle, tests/support/visibility_oracle.h) at the
// surface the camera ray through the pixel's centre meets. The ray caster is
// fast enough for every pixel (about a million rays at 640x360, under a
// second), so no 8192^2 maps stand in for it. The pipeline with shadows off is the same sum with
// every vis_i = 1: ShadowReference::linearityMaxAbs checks the sum against it.
// Only the lighting pass reads shadows; what the forward pass draws after it
// (light markers, blended glass) is left out of the error images.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench.h"
#include "rgraph/graph.h"

namespace rgraph {
class ShaderLibrary;
}

namespace rgraph::cli::bench {

struct ShadowRow {
  std::string method;             // none, hard, pcf3, pcf5, pcf7, pcss, evsm
  int mapSize = 2048;             // texels per side of every map (shadow_map "size")
  int cascades = 4;               // of the sun (shadow_map "cascades")
  std::vector<std::string> axes;  // within the shadows axis: method, resolution, cascades, baseline
  Extent size{640, 360};
  std::vector<double> frameMs, shadowMs;  // whole frame; the shadow_map passes together
  ImageError err;                         // against the exact-visibility image
  uint64_t atlasBytes = 0, allocatedBytes = 0;
  uint32_t atlasLayers = 0;
  std::string skipped;  // non-empty: not run, and why (a filter the lighting pass does not offer)
  std::string error;    // non-empty: the row failed
  bool ok() const { return error.empty(); }
  bool measured() const { return ok() && skipped.empty() && !frameMs.empty(); }
  std::string label() const;  // "pcf3 2048 c4", "none"
};

struct ShadowPlan {
  Extent size{640, 360};
  int rounds = 2;                             // every row is timed once per round (runShadows)
  int warm = 1, timedFrames = 3;              // per round
  bool everyMethodAtEveryResolution = false;  // full run: the resolution sweep for every method, not only hard and pcf3
  bool tiny = false;                          // --smoke: four rows at 160x90 for the tests
};
ShadowPlan shadowPlan(bool quick, bool smoke);
std::vector<ShadowRow> planShadows(const ShadowPlan& plan);

// How the reference was made, for results.json.
struct ShadowReference {
  std::string how;                  // one line
  std::vector<std::string> lights;  // the casting lights, as "directional0", "spot1", "point3"
  size_t pixels = 0;                // probed (the camera ray met a caster)
  size_t shadowRays = 0;
  double oracleSeconds = 0.0;     // ray casting, wall clock
  double linearityMaxAbs = -1.0;  // HDR: |none - (base + sum (L_i - D))|, -1: no "none" row
  double shadowedShare = 0.0;     // of probed pixel-light pairs: a caster in between
};

// Renders every row; returns the number that failed (skipped rows are not failures).
size_t runShadows(std::vector<ShadowRow>& rows, const ShadowPlan& plan, const std::string& pipelineDir,
                  ShaderLibrary& shaders, ShadowReference& reference);
nlohmann::json shadowJson(const ShadowRow& r);
ShadowRow shadowFromJson(const nlohmann::json& j);  // for --replot: every field shadowJson writes
nlohmann::json shadowReferenceJson(const ShadowReference& r);
// "shadows" into checks: the cost of shadows, the best row, the cheapest
// within 1 dB of it at <= half its time, hard at 512 against 2048.
void shadowChecks(const std::vector<ShadowRow>& rows, nlohmann::json& checks, std::vector<std::string>& summary);
// The figure table "shadows" (markdown) and the chart shadows_ms_vs_error.
std::string shadowTable(const std::vector<ShadowRow>& rows);
void drawShadowChart(const std::string& dir, const std::vector<ShadowRow>& rows, const std::string& machine);

}  // namespace rgraph::cli::bench
