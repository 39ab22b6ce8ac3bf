// Bounds at a pose (rgraph/animation.h: PosedBounds, poseScene): what
// RenderScene::setTime and callers posing a Scene themselves (the bench's
// walk rows) give culling, so that a bent limb is never culled.
#include <span>
#include <vector>

#include "rgraph/animation.h"
#include "rgraph/scene.h"

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

Bounds PosedBounds::operator()(const Scene& scene, const Pose& pose, const Primitive& p) {
  const MeshData& mesh = scene.meshes[size_t(p.mesh)];
  const SceneAnimation& a = scene.animation;
  if (p.node < 0 || size_t(p.node) >= a.nodes.size()) return p.worldBounds(mesh.bounds);
  const SceneNode& node = a.nodes[size_t(p.node)];
  Bounds local = mesh.bounds;
  if (!node.weights.empty() && !mesh.morphTargets.empty()) {
    if (targetBounds_.size() != scene.meshes.size()) targetBounds_.assign(scene.meshes.size(), {});
    std::vector<Bounds>& t = targetBounds_[size_t(p.mesh)];
    if (t.size() != mesh.morphTargets.size()) t = deltaBounds(mesh);
    local = morphedBounds(local, t, pose.nodeWeights(a, p.node));
  }
  if (node.skin >= 0 && mesh.skinned()) {
    Bounds b;
    for (const glm::mat4& j : pose.skinJoints(a, node.skin)) b.expand(local.transformed(j));
    return b;
  }
  return p.worldBounds(local);
}

void poseScene(Scene& scene, const Pose& pose, PosedBounds& bounds) {
  const SceneAnimation& a = scene.animation;
  for (Primitive& p : scene.primitives) {
    if (p.node < 0 || size_t(p.node) >= a.nodes.size()) continue;
    const SceneNode& node = a.nodes[size_t(p.node)];
    if (!(node.skin >= 0 && scene.meshes[size_t(p.mesh)].skinned())) p.transform = pose.world[size_t(p.node)];
    p.bounds = bounds(scene, pose, p);
  }
}

}  // namespace rgraph
