// RenderScene::setTime (rgraph/renderer.h): the scene posed at the caller's
// clock. Objects drawn by animated nodes get their node's world matrix (the
// objects path: GpuScene sees a moved object and its previous matrix), the
// GPU copy the pose's joint matrices and morph weights, and deformed
// objects bounds that hold the pose.
#include <cmath>
#include <string>
#include <vector>

#include "render_scene_impl.h"
#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/renderer.h"

namespace rgraph {

void RenderScene::Impl::applyPose(double seconds, int animation) {
  const SceneAnimation& a = scene.animation;
  if (animation != kRestPose && animation != kAllAnimations &&
      (animation < 0 || size_t(animation) >= a.animations.size()))
    throw RuntimeError(where() + ": RenderScene::setTime: no animation " + std::to_string(animation) +
                       " (the scene has " + std::to_string(a.animations.size()) + ")");
  evaluatePose(a, seconds, animation, pose);
  time = seconds;
  if (givenWorld.size() != a.nodes.size()) {
    // Before the first pose: what the loader gave the objects (the rest pose).
    givenWorld.assign(a.nodes.size(), glm::mat4(1.0f));
    for (const Primitive& p : scene.primitives)
      if (p.node >= 0 && size_t(p.node) < givenWorld.size()) givenWorld[size_t(p.node)] = p.transform;
  }
  for (Primitive& p : scene.primitives) {
    if (p.node < 0 || size_t(p.node) >= a.nodes.size()) continue;
    const bool skinned = a.nodes[size_t(p.node)].skin >= 0 && scene.meshes[size_t(p.mesh)].skinned();
    // Rigid: the node's matrix when it moved since it was last given (else
    // the caller's transform stands); skinning ignores the node's matrix.
    const glm::mat4& world = pose.world[size_t(p.node)];
    if (!skinned && world != givenWorld[size_t(p.node)]) p.transform = world;
    p.bounds = posedBounds(scene, pose, p);
  }
  for (const Primitive& p : scene.primitives)
    if (p.node >= 0 && size_t(p.node) < givenWorld.size()) givenWorld[size_t(p.node)] = pose.world[size_t(p.node)];
  if (gpu && gpu->deforms()) gpu->setPose(pose.joints, pose.weights);
}

void RenderScene::setTime(double seconds, int animation) {
  if (!std::isfinite(seconds))
    throw RuntimeError(impl_->where() + ": RenderScene::setTime: the time must be a finite number of seconds (got " +
                       std::to_string(seconds) + ")");
  if (impl_->scene.animation.empty()) {
    impl_->time = seconds;
    return;
  }
  impl_->applyPose(seconds, animation);
}

double RenderScene::time() const { return impl_->time; }

}  // namespace rgraph
