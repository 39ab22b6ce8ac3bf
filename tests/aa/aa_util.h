// Helpers of the anti-aliasing tests (issue 13): shipped pipelines loaded with
// their plugins, several consecutive frames through one executor (history
// resources need them), a supersampled reference, and the measures the tests
// assert on (PSNR over a pixel mask, edge masks, temporal variance).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "support/render_util.h"

namespace rgraph::aatest {

using rtest::Image;
using Mask = std::vector<bool>;  // one entry per pixel, rows top-down

// pipelines/<name>, plugins loaded into processRegistry() (rgraph/pipeline_load.h).
PipelineConfig shippedPipeline(const std::string& name);

// One executor rendering consecutive frames of a scene the test may edit
// between frames (primitive transforms: the executor reads them each frame).
class Frames {
 public:
  Frames(const PipelineConfig& cfg, const Scene& scene, Extent size, ShaderLibrary& shaders);
  Image next();  // renders a frame, reads the output
  Executor& exec() { return *exec_; }

 private:
  std::unique_ptr<Executor> exec_;
};

// `cfg` rendered at `factor` times `size` and box-filtered back to `size`
// (factor^2 samples per pixel, no jitter): the reference of edge quality.
Image supersampled(const PipelineConfig& cfg, const Scene& scene, Extent size, int factor, ShaderLibrary& shaders);

// Pixels where `ref` has a strong gradient: some channel differs from a
// 4-neighbour by at least `threshold` levels.
Mask edgeMask(const Image& ref, int threshold);
// Pixels at least `radius` pixels (Chebyshev) away from every pixel of `mask`.
Mask awayFrom(const Mask& mask, Extent e, int radius);
size_t count(const Mask& m);

struct Error {
  double mse = 0.0, psnr = 0.0;  // over RGB of the selected pixels (8-bit levels); psnr +inf when equal
  int maxAbs = 0;
  size_t pixels = 0;
  std::string describe() const;
};
Error measure(const Image& a, const Image& b, const Mask* mask = nullptr);

// Pixels where `img` differs from `background` by more than `tolerance`
// in some channel (where an object covers the frame).
Mask differsFrom(const Image& img, const Image& background, int tolerance);

// The errors `rgraph validate` reports for pipeline text `json` (named
// `name` in messages) compiled at `output` (graph, pass checks; no shader
// checks), one formatDiagnostic line each. Fails the test when it does not load.
std::string checkErrors(const std::string& json, const std::string& name, Extent output);

// The TAA stage: a flat grey wall (z = -2, facing the camera) lit evenly by a
// directional light along -Z plus ambient, a red cube (primitive kCube,
// half-size 0.35) at the origin; camera at (0, 0, 5) looking down -Z. Flat
// lighting on purpose: away from edges every correct method gives the same
// colour, so what is left of an old frame (a trail, a stale history) shows.
inline constexpr size_t kCube = 1;
Scene makeStage();

}  // namespace rgraph::aatest
