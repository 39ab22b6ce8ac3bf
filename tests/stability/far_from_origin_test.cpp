// Case 2: a scene ~4,096 units from the origin. The learnopengl and pbr
// layouts store world positions in rgba16f, whose step at 4096 is 4 units:
// every surface of a 6-unit scene collapses onto a few lattice points and the
// lighting is wrong. The compact layout stores no position (it is rebuilt from
// depth with the inverse projection and view) and the fp32 layout stores
// float32: both stay close to the forward reference. Each layout is rendered
// at the origin and translated by (4096, 0, 4096) and compared with forward_lit
// (no cut-off); fullscreen lighting with no cut-off too, so the G-buffer is the
// only difference.
#include <cmath>
#include <iostream>

#include "stability_util.h"

using namespace rgraph;
using namespace rgraph::stab;

namespace {

constexpr Extent kSize{128, 128};
const glm::vec3 kFar{4096.0f, 0.0f, 4096.0f};

struct Case {
  const char* name;
  GBufferSpec spec;
  bool halfPositions;  // stores world position in rgba16f
};
const Case kCases[] = {
    {"fp32", {"fp32", ""}, false},  // first: its positions are the reference
    {"learnopengl", {"learnopengl", ""}, true},
    {"pbr", {"pbr", ""}, true},
    {"compact-depth24", {"compact", "depth24_stencil8"}, false},
    {"compact-depth32f", {"compact", "depth32f"}, false},
};

// Tolerance of the layouts that keep precision far from the origin, and of
// every layout at the origin. 2/255 is what the deferred pipelines are held
// to against forward_lit elsewhere (rgba8 albedo alone rounds by 0.5/255);
// 50 dB is the bar for the compact layout on the default scene.
// Measured (llvmpipe): compact 2/255 and 55.9 dB at 4096 (57.3 dB at the
// origin), fp32 0/255; learnopengl and pbr 190/255 and 14.6 dB at 4096.
constexpr int kMaxAbs = 2;          // 8-bit levels
constexpr double kMinPsnr = 50.0;   // dB

// The world position a lighting pass sees, per covered pixel: the position
// target, or (compact) gbuffer.glsl's positionFromDepth redone in float with
// the matrices GpuScene uploads.
std::vector<glm::vec3> seenPositions(const Frame& f, const Scene& scene, bool fromDepth) {
  std::vector<glm::vec3> p(static_cast<size_t>(f.size.width) * f.size.height, glm::vec3(NAN));
  const float aspect = float(f.size.width) / float(f.size.height);
  const glm::mat4 invProj = glm::inverse(scene.camera.projection(aspect));
  const glm::mat4 invView = glm::inverse(scene.camera.view());
  for (size_t i = 0; i < p.size(); ++i) {
    if (fromDepth) {
      const float depth = f.target("gDepth")[i * 4];
      if (!(depth < 1.0f)) continue;
      const size_t x = i % f.size.width, rowGl = f.size.height - 1 - i / f.size.width;
      const glm::vec2 uv((float(x) + 0.5f) / float(f.size.width), (float(rowGl) + 0.5f) / float(f.size.height));
      glm::vec4 view = invProj * glm::vec4(uv * 2.0f - 1.0f, depth * 2.0f - 1.0f, 1.0f);
      view /= view.w;
      p[i] = glm::vec3(invView * view);
    } else {
      const auto& t = f.target("gPosition");
      if (t[i * 4 + 3] > 0.5f) p[i] = {t[i * 4], t[i * 4 + 1], t[i * 4 + 2]};
    }
  }
  return p;
}

}  // namespace

TEST_F(Stability, FarFromOriginHalfFloatPositions) {
  ASSERT_EQ(halfUlp(4096.0), 4.0) << "rgba16f step at 4096";
  const LightingParams l{"blinn_phong", "classic", 0.0};
  const PipelineConfig forward = pipelineFromJson(forwardPipeline(l), "forward");
  for (const bool far : {false, true}) {
    const glm::vec3 offset = far ? kFar : glm::vec3(0.0f);
    const Scene scene = smallStillLife(offset);
    const Frame ref = renderFrame(forward, scene, kSize);
    // The scene covers most of the picture (the comparison is not vacuous).
    size_t covered = 0;
    for (size_t i = 0; i < ref.rgba.size(); i += 4) covered += (ref.rgba[i] | ref.rgba[i + 1] | ref.rgba[i + 2]) > 8;
    ASSERT_GT(covered, ref.rgba.size() / 4 / 2);

    std::vector<glm::vec3> truePositions;  // the fp32 layout's (the first case)
    for (const Case& c : kCases) {
      const std::string name = std::string(c.name) + (far ? "@4096" : "@origin");
      const bool compact = c.spec.layout == "compact";
      const Frame f = renderFrame(pipelineFromJson(fullscreenPipeline(c.spec, l), name), scene, kSize,
                                  {compact ? "gDepth" : "gPosition"});
      const std::vector<glm::vec3> seen = seenPositions(f, scene, compact);
      if (truePositions.empty()) truePositions = seen;
      double posErr = 0.0;
      for (size_t i = 0; i < seen.size(); ++i)
        if (!std::isnan(seen[i].x) && !std::isnan(truePositions[i].x))
          posErr = std::max(posErr, double(glm::length(seen[i] - truePositions[i])));
      const Diff d = compare8(ref.rgba, f.rgba, kSize);
      std::cout << "[ measure  ] " << (far ? "at (4096,0,4096)" : "at the origin   ") << " layout " << c.name
                << ": position error up to " << posErr << " units; vs forward_lit " << d.describe() << std::endl;
      const std::string key = std::string(c.name) + (far ? "_far" : "_origin");
      RecordProperty(key + "_max_abs_8bit", d.maxAbs);
      RecordProperty(key + "_psnr_db", psnrText(d.psnr));
      RecordProperty(key + "_position_error", std::to_string(posErr));
      const bool mustHold = !far || !c.halfPositions;
      if (mustHold) {
        EXPECT_LE(d.maxAbs, kMaxAbs) << name << ": " << d.describe() << " "
                                     << saveImage(f.rgba, kSize, "far-" + name) << " "
                                     << saveImage(ref.rgba, kSize, std::string("far-forward") + (far ? "@4096" : "@origin"));
        EXPECT_GE(d.psnr, kMinPsnr) << name << ": " << d.describe();
      } else {
        // The documented failure: half-float positions 4096 units out.
        EXPECT_GE(d.maxAbs, 32) << name << " was expected to fail far from the origin: " << d.describe();
        EXPECT_LT(d.psnr, 30.0) << name << " was expected to fail far from the origin: " << d.describe();
        // Positions snap to the half-float lattice: step 4 at 4096.
        EXPECT_GE(posErr, 1.0) << name;
        EXPECT_LE(posErr, 4.0 * std::sqrt(3.0)) << name;
      }
    }
  }
}
