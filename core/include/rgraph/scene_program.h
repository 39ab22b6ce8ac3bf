// Programs that draw the scene: their vertex shader is the built-in
// scene.vert. It has two variants: the executor adds kSceneAnimationDefine
// for a scene that deforms (skins, morph targets: GpuScene::sceneDeforms),
// and `rgraph validate`, which does not know the scene, checks both, so that
// what validate accepts renders with any scene.
#pragma once

#include <string>

#include "rgraph/pass.h"

namespace rgraph {

inline constexpr const char* kSceneAnimationDefine = "SCENE_ANIMATION";

// Whether `spec`'s vertex shader is scene.vert (any folder: a name ending in "scene.vert").
inline bool drawsScene(const ShaderProgramSpec& spec) {
  const std::string name = "scene.vert";
  return spec.vert.size() >= name.size() && spec.vert.compare(spec.vert.size() - name.size(), name.size(), name) == 0;
}

}  // namespace rgraph
