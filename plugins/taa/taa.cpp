// The TAA plugin: temporal anti-aliasing. With the pipeline's sub-pixel
// jitter (config "jitter": N) each frame samples a different point of every
// pixel; this pass accumulates them over frames into its output, whose
// previous-frame copy (a resource with "history_of" the output) it reads
// back the next frame. shaders/taa.frag says how the history is reprojected
// with the motion vectors, clipped in YCoCg and rejected where it is stale.
//
// It resolves the HDR image, before tone mapping: the accumulation is a
// linear average of light, which is right in HDR and wrong after a tone curve
// (averaging display values darkens bright edges); Karis' inverse-luma
// weights keep a bright sample from flickering, which is what resolving
// after tonemap would otherwise buy. Tone mapping then runs once on the
// resolved image.
#include <GL/glcorearb.h>

#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

class TaaPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    historyValid_.set(ctx.historyValid("history"));
    historyWeight_.set(static_cast<float>(p.getNumber("history_weight")));
    motionWeight_.set(static_cast<float>(p.getNumber("motion_history_weight")));
    clipGamma_.set(static_cast<float>(p.getNumber("clip_gamma")));
    reject_.set(static_cast<float>(p.getNumber("reject_distance")));
    sharpen_.set(static_cast<float>(p.getNumber("sharpen")));
    currentFilter_.set(static_cast<float>(p.getNumber("current_filter")));
    hasVelocityDepth_.set(ctx.bound("velocity_depth") ? 1 : 0);
    ctx.gpuScene()->bindFrame();  // the cameras, for motion not in the velocity input
  }
  ProgramUniform historyValid_{this, "u_historyValid"}, historyWeight_{this, "u_historyWeight"};
  ProgramUniform clipGamma_{this, "u_clipGamma"}, reject_{this, "u_rejectDistance"}, sharpen_{this, "u_sharpen"};
  ProgramUniform hasVelocityDepth_{this, "u_hasVelocityDepth"}, motionWeight_{this, "u_motionHistoryWeight"};
  ProgramUniform currentFilter_{this, "u_currentFilter"};
};

// Every image the resolve reads per pixel has the output's size, and the
// history is this pass's own output as the last frame left it: bound to
// anything else, the resolve would never accumulate (or blend a stranger's image).
void checkHistory(const PassCheckContext& ctx, PassChecks& checks) {
  const CheckedSlot* history = ctx.find("history");
  const CheckedSlot* output = ctx.find("output");
  if (!history || !output) return;
  if (history->historyOf.empty())
    checks.slotError("history", "'" + history->resource + "' is not a history resource; declare one with \"history_of\": \"" +
                                    output->resource + "\" and bind it here");
  else if (history->historyOf != output->resource)
    checks.slotError("history", "'" + history->resource + "' holds the history of '" + history->historyOf +
                                    "', not of this pass's output '" + output->resource + "'");
}

void registerTaa(PluginHost& host) {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("taa",
      "Temporal anti-aliasing: jittered frames accumulated through a reprojected, clipped history");
  d.slots = {
      slot("color", Access::sampled, true, SlotDecl::Load::never, "this frame's HDR image (jittered)", hdrFormats()),
      // Reprojected: the bicubic history filter is built from bilinear taps.
      sampledWith(slot("history", Access::sampled, true, SlotDecl::Load::never,
                       "last frame's output: a resource with \"history_of\" this pass's output", hdrFormats()),
                  bilinearClamped()),
      slot("velocity", Access::sampled, true, SlotDecl::Load::never,
           "motion vectors in UV units, uv_now - uv_prev (the geometry pass's velocity slot)", velocityFormats()),
      slot("depth", Access::sampled, true, SlotDecl::Load::never,
           "this frame's depth, of everything drawn (velocity dilation; camera motion where velocity is 0)",
           depthFormats()),
      // Optional: a forward pass draws after the G-buffer without motion
      // vectors (light boxes, particles). Where `depth` is nearer than this,
      // the velocity input holds the motion of the surface behind what is
      // seen: the pixel moves with the camera instead, reprojected by depth.
      slot("velocity_depth", Access::sampled, false, SlotDecl::Load::never,
           "the depth the velocity input was drawn with (the geometry pass's); where depth is nearer, "
           "something drawn later without motion vectors is seen: it moves with the camera",
           depthFormats()),
      slot("output", Access::color_attachment, true, SlotDecl::Load::never,
           "the resolved HDR image, next frame's history", hdrFormats()),
  };
  d.params = {
      ranged("history_weight", ParamType::number, 0.9, 0.0, 0.99,
             "share of the reprojected history in each frame (higher: smoother, slower to follow changes)"),
      ranged("motion_history_weight", ParamType::number, 0.6, 0.0, 0.99,
             "history_weight where the pixel moves: each frame's reprojection resamples and clips the history, "
             "so in motion a shorter history is closer to the supersampled image (docs/performance.md, aa axis)"),
      ranged("clip_gamma", ParamType::number, 1.25, 0.25, 4.0,
             "history clip box: mean +- gamma standard deviations of the 3x3 in YCoCg (smaller: less ghosting)"),
      ranged("reject_distance", ParamType::number, 2.0, 0.0, 100.0,
             "history this many box sizes outside the 3x3's box is disoccluded: dropped, not clipped"),
      ranged("sharpen", ParamType::number, 0.0, 0.0, 1.0,
             "unsharp mask on the current frame against the blur of accumulation (0 off)"),
      ranged("current_filter", ParamType::number, 0.4, 0.0, 2.0,
             "sigma in pixels of the current frame's reconstruction at the unjittered pixel centre from its "
             "jittered 3x3 (0: the pixel alone)"),
  };
  d.programs = gl::fullscreenPrograms(
      host.shaderPath("taa.frag"),
      {{"color", "u_color", 0}, {"history", "u_history", 1}, {"velocity", "u_velocity", 2}, {"depth", "u_depth", 3},
       {"velocity_depth", "u_velocityDepth", 4}});
  d.rules = {sameSizeRule({"color", "history", "velocity", "depth", "velocity_depth", "output"}),
             {"history is the history resource (\"history_of\") of the resource output writes", checkHistory}};
  d.needsScene = true;  // the Frame block's cameras
  d.create = [] { return std::make_unique<TaaPass>(); };
  host.addPassType(std::move(d));
}

}  // namespace

RGRAPH_PLUGIN("taa", registerTaa)
