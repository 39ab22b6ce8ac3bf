// GpuScene's draws from views other than the camera (drawView, drawLayered,
// drawEachLayer) and the primitive selection all its scene draws share.
//
// A view's Frame block is written into a ring of slots of its own buffer and
// bound at uniform buffer 0 with glBindBufferRange for its draws; the camera's
// blocks (frame_, frameUnjittered_) are never written here, and bindFrame()
// puts the camera's back after each call, so later passes and later draws of
// the same pass see the camera as if no view had been drawn.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "frame_block.h"
#include "rgraph/error.h"
#include "rgraph/gl/context.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass.h"
#include "rgraph/scene.h"

namespace rgraph {
namespace {

using detail::FrameBlock;
using detail::kLayerViewsPerBlock;
using detail::LayerViewsBlock;

// Slots of each ring: a slot is rewritten only after this many later calls,
// so a draw still queued on the GPU rarely holds up the write (GL keeps
// the result right either way).
constexpr uint32_t kViewSlots = 16;
constexpr uint32_t kLayerSlots = 4;

glm::vec3 eyeOf(const GpuScene::View& v) { return v.eye ? *v.eye : glm::vec3(glm::inverse(v.view)[3]); }

uint32_t alignUp(uint32_t bytes, uint32_t alignment) { return (bytes + alignment - 1) / alignment * alignment; }


}  // namespace

bool GpuScene::selects(Filter filter, size_t primitive) const {
  const Primitive& p = scene_.primitives[primitive];
  if (!visible(primitive)) return false;  // hidden (RenderScene::setVisible)
  const bool blend = scene_.materials[p.material].alphaMode == AlphaMode::blend;
  switch (filter) {
    case Filter::all: return true;
    case Filter::opaque: return !blend;
    case Filter::blend: return blend;
    case Filter::shadowCasters: return scene_.castsShadows(p);
  }
  return false;
}

std::vector<size_t> GpuScene::select(Filter filter, bool backToFront, glm::vec3 eye) const {
  std::vector<size_t> order;
  for (size_t i = 0; i < scene_.primitives.size(); ++i)
    if (selects(filter, i)) order.push_back(i);
  if (backToFront) {
    auto dist = [&](size_t i) { return glm::length(scene_.primitives[i].bounds.center() - eye); };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return dist(a) > dist(b); });
  }
  return order;
}

void GpuScene::ensureViewBuffers() {
  if (views_) return;
  GLint alignment = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const uint32_t align = static_cast<uint32_t>(std::max(alignment, 16));
  viewStride_ = alignUp(sizeof(FrameBlock), align);
  layerStride_ = alignUp(sizeof(LayerViewsBlock), align);
  views_ = gl::createBuffer();
  glNamedBufferStorage(views_.id(), GLsizeiptr(viewStride_) * kViewSlots, nullptr, GL_DYNAMIC_STORAGE_BIT);
  layerViews_ = gl::createBuffer();
  glNamedBufferStorage(layerViews_.id(), GLsizeiptr(layerStride_) * kLayerSlots, nullptr, GL_DYNAMIC_STORAGE_BIT);
}

bool GpuScene::supportsLayeredDraw() const {
  if (!layeredSupport_)
    layeredSupport_ = hasExtension("GL_ARB_shader_viewport_layer_array") || hasExtension("GL_AMD_vertex_shader_layer");
  return *layeredSupport_;
}

GpuScene::Viewport GpuScene::applyViewport(const View& view) const {
  if (view.viewport) {
    const Viewport& v = *view.viewport;
    glViewport(v.x, v.y, static_cast<GLsizei>(v.width), static_cast<GLsizei>(v.height));
    if (record_) {
      // The record knows viewports at (0, 0) only (GlBindings).
      const bool origin = v.x == 0 && v.y == 0;
      record_->viewportWidth = origin ? v.width : GlBindings::kUnknown;
      record_->viewportHeight = origin ? v.height : GlBindings::kUnknown;
    }
    return v;
  }
  GLint current[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_VIEWPORT, current);
  return Viewport{current[0], current[1], static_cast<uint32_t>(current[2]), static_cast<uint32_t>(current[3])};
}

void GpuScene::bindViewBlock(const View& view, Viewport viewport) {
  FrameBlock f{};
  const float w = static_cast<float>(std::max(viewport.width, 1u));
  const float h = static_cast<float>(std::max(viewport.height, 1u));
  f.view = view.view;
  f.proj = view.proj;
  f.viewProj = view.proj * view.view;
  f.invView = glm::inverse(view.view);
  f.invProj = glm::inverse(view.proj);
  f.cameraPos = glm::vec4(eyeOf(view), 1.0f);
  f.viewport = glm::vec4(w, h, 1.0f / w, 1.0f / h);
  detail::fillSceneMembers(f, scene_);
  // No jitter, no camera motion: a view is drawn as it is this frame.
  f.viewProjNoJitter = f.prevViewProj = f.viewProj;
  f.frame = frameIndex_;
  const uint32_t offset = viewStride_ * (nextView_++ % kViewSlots);
  glNamedBufferSubData(views_.id(), offset, sizeof(FrameBlock), &f);
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, views_.id(), offset, sizeof(FrameBlock));
  boundFrame_ = 0;  // a range of views_, not a camera block: bindFrame binds again
}

void GpuScene::drawView(uint32_t program, const View& view) {
  ensureViewBuffers();
  const Viewport viewport = applyViewport(view);
  bindViewBlock(view, viewport);
  drawList(program, select(view.filter, view.backToFront, eyeOf(view)), view.cull, 1);
  bindFrame();
}

void GpuScene::drawEachLayer(uint32_t program, const std::vector<View>& views,
                             const std::function<void(size_t)>& bindLayer) {
  for (size_t i = 0; i < views.size(); ++i) {
    bindLayer(i);
    drawView(program, views[i]);
  }
}

void GpuScene::drawLayered(uint32_t program, const std::vector<View>& views, uint32_t firstLayer) {
  if (views.empty()) return;
  if (!supportsLayeredDraw())
    throw RuntimeError("GpuScene::drawLayered: this GL device has neither GL_ARB_shader_viewport_layer_array nor "
                       "GL_AMD_vertex_shader_layer (gl_Layer from the vertex shader); draw one layer at a time with "
                       "drawEachLayer (supportsLayeredDraw() says which)");
  const View& first = views.front();
  for (const View& v : views)
    if (v.cull != first.cull || v.filter != first.filter || v.backToFront != first.backToFront ||
        v.viewport.has_value() != first.viewport.has_value() ||
        (v.viewport && (v.viewport->x != first.viewport->x || v.viewport->y != first.viewport->y ||
                        v.viewport->width != first.viewport->width || v.viewport->height != first.viewport->height)))
      throw RuntimeError("GpuScene::drawLayered: every view must have the first one's viewport, cull, filter and "
                         "backToFront (one draw covers them all); draw views that differ with drawEachLayer");
  ensureViewBuffers();
  // Binding 0: the first view's Frame block (what the fragment shader reads:
  // u_viewport, u_cameraPos; the vertex shader takes each layer's matrix from LayerViews).
  bindViewBlock(first, applyViewport(first));
  const std::vector<size_t> order = select(first.filter, first.backToFront, eyeOf(first));
  for (size_t start = 0; start < views.size(); start += kLayerViewsPerBlock) {
    const size_t n = std::min<size_t>(kLayerViewsPerBlock, views.size() - start);
    LayerViewsBlock block{};
    block.base = glm::ivec4(static_cast<int>(firstLayer + start), static_cast<int>(n), 0, 0);
    for (size_t i = 0; i < n; ++i) block.viewProj[i] = views[start + i].proj * views[start + i].view;
    const uint32_t offset = layerStride_ * (nextLayerSlot_++ % kLayerSlots);
    const GLsizeiptr bytes = static_cast<GLsizeiptr>(16 + n * sizeof(glm::mat4));
    glNamedBufferSubData(layerViews_.id(), offset, bytes, &block);
    glBindBufferRange(GL_UNIFORM_BUFFER, 1, layerViews_.id(), offset, sizeof(LayerViewsBlock));
    drawList(program, order, first.cull, static_cast<uint32_t>(n));
  }
  glBindBufferBase(GL_UNIFORM_BUFFER, 1, 0);  // nothing else uses binding 1: leave it as found
  bindFrame();
}

}  // namespace rgraph
