// Executor: what carries over from one frame to the next. The frame counter,
// the previous frame's view-projection (motion vectors) and the jitter phases
// go into the scene's Frame block; history resources (ResourceDecl::historyOf)
// get their source's content of the previous frame, copied after each frame,
// and start cleared and invalid after a build, a resize or a camera cut.
#include <GL/glcorearb.h>

#include <algorithm>

#include "executor_internal.h"
#include "rgraph/gl/format.h"
#include "rgraph/scene.h"

namespace rgraph {

using exec_detail::HistoryCopy;

// Both ends of every history pair: their content matters across frames, so
// reuseTextures() neither offers nor takes them (another executor would
// overwrite them, or hand over content this one must not see).
std::vector<bool> Executor::Impl::keptPhysicals(const Plan& plan) {
  std::vector<bool> kept(plan.physical.size(), false);
  for (const PlannedResource& pr : plan.resources)
    if ((pr.historyOf.valid() || pr.history.valid() || pr.persistent) && pr.physical.valid())
      kept[pr.physical.value()] = true;
  return kept;
}

void Executor::Impl::planHistory() {
  std::vector<HistoryCopy> before = std::move(historyCopies);
  historyCopies.clear();
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const PlannedResource& pr = plan.resources[r];
    if (!pr.historyOf.valid()) continue;
    const exec_detail::ResourceObject& to = resources[r];
    const exec_detail::ResourceObject& from = resources[pr.historyOf.value()];
    // The compiler refuses a history whose source differs in format, size or
    // samples; what is not created (an unused history) is not copied.
    if (!to.texture || !from.texture) continue;
    HistoryCopy c;
    c.source = pr.historyOf;
    c.history = ResourceIndex(r);
    c.from = from.texture;
    c.to = to.texture;
    c.format = to.format;
    c.extent = to.extent;
    c.mips = std::min(to.mips, from.mips);
    c.samples = to.samples;
    c.target = gl::textureTarget(to.samples, to.layers, to.cube);
    c.arrayLayers = to.layers * (to.cube ? 6 : 1);
    historyCopies.push_back(c);
  }
  // An import that replaced either texture (Executor::importTexture) leaves
  // nothing of the previous frame in the history.
  auto sameTextures = [](const HistoryCopy& a, const HistoryCopy& b) { return a.from == b.from && a.to == b.to; };
  if (!std::equal(before.begin(), before.end(), historyCopies.begin(), historyCopies.end(), sameTextures))
    historyHeld = false;
}

// The Frame block of this executor's frame: its camera, the frame number (the
// jitter phase, animation time) and the previous frame's view-projection.
void Executor::Impl::updateFrameBlock() {
  if (!gpuScene) return;
  FrameMotion motion;
  motion.frame = frame;
  motion.jitterPhases = pipeline.jitterPhases;
  motion.prevViewProj = prevViewProj;
  prevViewProj = gpuScene->updateFrame(size, camera ? *camera : gpuScene->scene().camera, motion);
}

// Zeros in every history texture (all levels; glClearTexImage with no data
// clears to zero in any format) when they hold nothing of a previous frame.
void Executor::Impl::beginHistory() {
  if (historyHeld) return;
  for (const HistoryCopy& c : historyCopies) {
    const gl::GlFormat g = gl::glFormat(c.format);
    for (uint32_t level = 0; level < c.mips; ++level)
      glClearTexImage(c.to, static_cast<GLint>(level), g.format, g.type, nullptr);
  }
}

void Executor::Impl::endHistory() {
  for (const HistoryCopy& c : historyCopies) {
    const GLenum target = c.target;
    for (uint32_t level = 0; level < c.mips; ++level) {
      const auto w = static_cast<GLsizei>(std::max(1u, c.extent.width >> level));
      const auto h = static_cast<GLsizei>(std::max(1u, c.extent.height >> level));
      glCopyImageSubData(c.from, target, static_cast<GLint>(level), 0, 0, 0, c.to, target, static_cast<GLint>(level), 0,
                         0, 0, w, h, static_cast<GLsizei>(c.arrayLayers));
    }
  }
  historyHeld = true;
}

void Executor::cameraCut() {
  impl_->historyHeld = false;
  impl_->prevViewProj.reset();
}

uint64_t Executor::frameIndex() const { return impl_->frame; }

void Executor::invalidatePersistent() { impl_->persistentHeld = false; }

}  // namespace rgraph
