// std140 mirror of the Frame block (shaders/include/frame.glsl) and of the
// LayerViews block (shaders/include/layer_views.glsl): what gpu_scene.cpp
// writes for the camera and gpu_scene_view.cpp for other views. Internal to
// core/src/gl; GL-free (glm only), so tests/shadercheck can include it.
//
// kFrameBlockMembers lists FrameBlock's members for the test that holds the
// two declarations together: tests/shadercheck/frame_block_layout_test.cpp
// compares every member's offset and type here with glslang's reflection of
// the GLSL block, so moving a member or changing its type on either side fails
// there (the size check below alone misses two members of one size swapped).
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string_view>
#include <type_traits>

namespace rgraph {

struct Scene;

namespace detail {

// Every member is 16-byte aligned in std140, so the C++ layout matches with
// no padding of its own.
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
static_assert(std::is_standard_layout_v<FrameBlock>, "offsetof needs a standard-layout FrameBlock");

// A member's GLSL type spelling, from its C++ type (a new member type needs
// its spelling here, or the table below does not compile).
template <class T>
constexpr std::string_view glslTypeOf() {
  if constexpr (std::is_same_v<T, glm::mat4>) return "mat4";
  else if constexpr (std::is_same_v<T, glm::vec4>) return "vec4";
  else if constexpr (std::is_same_v<T, glm::ivec4>) return "ivec4";
  else static_assert(sizeof(T) == 0, "add this member type's GLSL spelling");
}

struct FrameBlockMember {
  std::string_view glslName;  // the member's name in frame.glsl
  size_t offset;              // offsetof in FrameBlock
  std::string_view glslType;  // from the C++ member's type
};

#define RGRAPH_FRAME_MEMBER(glsl, member) \
  FrameBlockMember { glsl, offsetof(FrameBlock, member), glslTypeOf<decltype(FrameBlock::member)>() }
// Every member of FrameBlock with the GLSL member it mirrors.
inline constexpr FrameBlockMember kFrameBlockMembers[] = {
    RGRAPH_FRAME_MEMBER("u_view", view),
    RGRAPH_FRAME_MEMBER("u_proj", proj),
    RGRAPH_FRAME_MEMBER("u_viewProj", viewProj),
    RGRAPH_FRAME_MEMBER("u_invView", invView),
    RGRAPH_FRAME_MEMBER("u_invProj", invProj),
    RGRAPH_FRAME_MEMBER("u_cameraPos", cameraPos),
    RGRAPH_FRAME_MEMBER("u_viewport", viewport),
    RGRAPH_FRAME_MEMBER("u_ambient", ambient),
    RGRAPH_FRAME_MEMBER("u_dirLightDir", dirLightDir),
    RGRAPH_FRAME_MEMBER("u_dirLightColor", dirLightColor),
    RGRAPH_FRAME_MEMBER("u_counts", counts),
    RGRAPH_FRAME_MEMBER("u_prevViewProj", prevViewProj),
    RGRAPH_FRAME_MEMBER("u_viewProjNoJitter", viewProjNoJitter),
    RGRAPH_FRAME_MEMBER("u_jitter", jitter),
    RGRAPH_FRAME_MEMBER("u_frame", frame),
};
#undef RGRAPH_FRAME_MEMBER

// The members that belong to the scene, not to a view: ambient, the first
// directional light, the light count (the camera's block and every view's
// block carry the same).
void fillSceneMembers(FrameBlock& f, const Scene& scene);

// The most views one LayerViews block holds (layer_views.glsl's array size):
// drawLayered draws more in chunks of this many.
inline constexpr int kLayerViewsPerBlock = 32;
struct LayerViewsBlock {
  glm::ivec4 base;  // x: the layer view 0 writes; y: the views in this block
  glm::mat4 viewProj[kLayerViewsPerBlock];
};
static_assert(sizeof(LayerViewsBlock) == 16 + kLayerViewsPerBlock * 64, "LayerViewsBlock must match std140");

}  // namespace detail
}  // namespace rgraph
