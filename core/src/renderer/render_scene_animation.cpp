// RenderScene::setTime (rgraph/renderer.h): the scene posed at the caller's
// clock. Objects drawn by animated nodes get their node's world matrix (the
// objects path: GpuScene sees a moved object and its previous matrix), the
// GPU copy the pose's joint matrices and morph weights, and deformed
// objects bounds that hold the pose.
#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "render_scene_impl.h"
#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/renderer.h"

namespace rgraph {
namespace {

// Each morph target's box of position deltas (empty: the target moves no position).
std::vector<Bounds> deltaBounds(const MeshData& m) {
  std::vector<Bounds> out;
  for (const MorphTarget& t : m.morphTargets) {
    Bounds b;
    for (const glm::vec3& d : t.positions) b.expand(d);
    out.push_back(b);
  }
  return out;
}

// The mesh's local box with the weighted target boxes added (interval
// arithmetic: a negative weight swaps a delta box's ends).
Bounds morphedBounds(const Bounds& local, const std::vector<Bounds>& targets, std::span<const float> weights) {
  if (local.empty()) return local;
  Bounds b = local;
  for (size_t i = 0; i < targets.size() && i < weights.size(); ++i) {
    if (targets[i].empty() || weights[i] == 0.0f) continue;
    const glm::vec3 a = weights[i] * targets[i].min, c = weights[i] * targets[i].max;
    b.min += glm::min(a, c);
    b.max += glm::max(a, c);
  }
  return b;
}

}  // namespace

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
  if (targetBounds.size() != scene.meshes.size()) targetBounds.assign(scene.meshes.size(), {});
  for (Primitive& p : scene.primitives) {
    if (p.node < 0 || size_t(p.node) >= a.nodes.size()) continue;
    const SceneNode& node = a.nodes[size_t(p.node)];
    const MeshData& mesh = scene.meshes[size_t(p.mesh)];
    const glm::mat4& world = pose.world[size_t(p.node)];
    Bounds local = mesh.bounds;
    if (!node.weights.empty() && !mesh.morphTargets.empty()) {
      std::vector<Bounds>& t = targetBounds[size_t(p.mesh)];
      if (t.size() != mesh.morphTargets.size()) t = deltaBounds(mesh);
      local = morphedBounds(local, t, pose.nodeWeights(a, p.node));
    }
    if (node.skin >= 0 && mesh.skinned()) {
      // A vertex is a weighted mean of its joints' images of it: inside the
      // union of the local box under every joint matrix of the skin.
      Bounds b;
      for (const glm::mat4& j : pose.skinJoints(a, node.skin)) b.expand(local.transformed(j));
      p.bounds = b;
      continue;
    }
    // Rigid: the node's matrix when it moved since it was last given (else
    // the caller's transform stands).
    if (world != givenWorld[size_t(p.node)]) p.transform = world;
    p.bounds = p.worldBounds(local);
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
