// std140 mirror of the Frame block (shaders/include/frame.glsl) and of the
// LayerViews block (shaders/include/layer_views.glsl): what gpu_scene.cpp
// writes for the camera and gpu_scene_view.cpp for other views. Internal to
// core/src/gl.
#pragma once

#include <glm/glm.hpp>

namespace rgraph {

struct Scene;

namespace detail {

// Every member is 16-byte aligned.
struct FrameBlock {
  glm::mat4 view, proj, viewProj, invView, invProj;
  glm::vec4 cameraPos;
  glm::vec4 viewport;
  glm::vec4 ambient;
  glm::vec4 dirLightDir;
  glm::vec4 dirLightColor;
  glm::ivec4 counts;
  // Motion and jitter (issue 13), appended so earlier offsets stay.
  glm::mat4 prevViewProj, viewProjNoJitter;
  glm::vec4 jitter;  // xy pixels, zw NDC
  glm::ivec4 frame;  // x frame index (mod 2^31), y jitter phases
};
static_assert(sizeof(FrameBlock) == 7 * 64 + 8 * 16, "FrameBlock must match the std140 layout");

// The members that belong to the scene, not to a view: ambient, the first
// directional light, the light count (the camera's block and every view's
// block carry the same).
void fillSceneMembers(FrameBlock& f, const Scene& scene);

// The most views one LayerViews block holds (layer_views.glsl's array size):
// drawLayered draws more in chunks of this many.
inline constexpr int kLayerViewsPerBlock = 32;
struct LayerViewsBlock {
  glm::ivec4 base;  // x: the layer instance 0 writes
  glm::mat4 viewProj[kLayerViewsPerBlock];
};
static_assert(sizeof(LayerViewsBlock) == 16 + kLayerViewsPerBlock * 64, "LayerViewsBlock must match std140");

}  // namespace detail
}  // namespace rgraph
