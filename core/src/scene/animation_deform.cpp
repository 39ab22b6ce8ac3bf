// The CPU reference deformer (a primitive's morphed and skinned vertices at
// a pose), and the bookkeeping of SceneAnimation: evaluation order, offsets
// into a pose's arrays, appending one scene's nodes to another's.
#include <algorithm>
#include <cmath>
#include <string>

#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph {

void SceneAnimation::updateLayout() {
  // Depth-first from the roots with an explicit stack (hierarchies as deep
  // as the file is long); a node on a cycle is never reached (loaders refuse cycles).
  std::vector<std::vector<int>> children(nodes.size());
  std::vector<int> roots;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const int p = nodes[i].parent;
    if (p >= 0 && size_t(p) < nodes.size())
      children[size_t(p)].push_back(int(i));
    else
      roots.push_back(int(i));
  }
  order.clear();
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    order.push_back(n);
    for (auto it = children[size_t(n)].rbegin(); it != children[size_t(n)].rend(); ++it) stack.push_back(*it);
  }
  jointCount = 0;
  for (SceneSkin& s : skins) {
    s.firstJoint = jointCount;
    jointCount += uint32_t(s.joints.size());
  }
  weightCount = 0;
  for (SceneNode& n : nodes) {
    n.firstWeight = weightCount;
    weightCount += uint32_t(n.weights.size());
  }
}

void appendAnimation(SceneAnimation& dst, SceneAnimation src, const glm::mat4& transform) {
  if (src.empty()) return;
  const int nodeBase = int(dst.nodes.size());
  const int skinBase = int(dst.skins.size());
  for (SceneNode& n : src.nodes) {
    if (n.parent >= 0)
      n.parent += nodeBase;
    else
      n.rootTransform = transform * n.rootTransform;
    if (n.skin >= 0) n.skin += skinBase;
    dst.nodes.push_back(std::move(n));
  }
  for (SceneSkin& s : src.skins) {
    for (int& j : s.joints) j += nodeBase;
    if (s.skeleton >= 0) s.skeleton += nodeBase;
    dst.skins.push_back(std::move(s));
  }
  for (Animation& a : src.animations) {
    for (AnimationChannel& c : a.channels) c.node += nodeBase;
    dst.animations.push_back(std::move(a));
  }
  dst.updateLayout();
}

namespace {

// The inverse transpose of m's upper 3x3 (normals); m itself where it is
// singular (a vertex whose weights are all 0), the normal then only renormalized.
glm::mat3 normalMatrix(const glm::mat4& m) {
  const glm::mat3 m3(m);
  const float det = glm::determinant(m3);
  return std::abs(det) > 1e-30f ? glm::transpose(glm::inverse(m3)) : m3;
}

glm::vec3 unit(const glm::vec3& v, const glm::vec3& fallback) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

}  // namespace

DeformedVertices deformPrimitive(const Scene& scene, const Pose& pose, size_t primitive) {
  if (primitive >= scene.primitives.size())
    throw RuntimeError("deformPrimitive: primitive " + std::to_string(primitive) + " does not exist (" +
                       std::to_string(scene.primitives.size()) + " primitives)");
  const Primitive& p = scene.primitives[primitive];
  const SceneAnimation& a = scene.animation;
  if (p.node >= 0 && (pose.world.size() != a.nodes.size() || pose.joints.size() != a.jointCount ||
                      pose.weights.size() != a.weightCount))
    throw RuntimeError("deformPrimitive: the pose was not evaluated for this scene's animation");
  const MeshData& m = scene.meshes.at(size_t(p.mesh));
  DeformedVertices out;
  out.positions = m.positions;
  out.normals = m.normals;
  out.tangents = m.tangents;
  const size_t n = m.vertexCount();

  // Morph targets, in the mesh's own space.
  if (p.node >= 0) {
    const std::span<const float> w = pose.nodeWeights(a, p.node);
    for (size_t k = 0; k < m.morphTargets.size() && k < w.size(); ++k) {
      if (w[k] == 0.0f) continue;
      const MorphTarget& t = m.morphTargets[k];
      for (size_t v = 0; v < n; ++v) {
        if (!t.positions.empty()) out.positions[v] += w[k] * t.positions[v];
        if (!t.normals.empty() && v < out.normals.size()) out.normals[v] += w[k] * t.normals[v];
        if (!t.tangents.empty() && v < out.tangents.size()) out.tangents[v] += glm::vec4(w[k] * t.tangents[v], 0.0f);
      }
    }
  }

  const int skin = p.node >= 0 ? a.nodes[size_t(p.node)].skin : -1;
  const std::span<const glm::mat4> joints = pose.skinJoints(a, skin);
  const bool skinned = skin >= 0 && m.skinned();
  const glm::mat4 rigid = p.node >= 0 ? pose.world[size_t(p.node)] : p.transform;
  const glm::mat3 rigidNormal = normalMatrix(rigid);
  for (size_t v = 0; v < n; ++v) {
    glm::mat4 xf = rigid;
    glm::mat3 nx = rigidNormal;
    if (skinned) {
      xf = glm::mat4(0.0f);
      for (const SkinInfluences& set : m.influences)
        for (int c = 0; c < 4; ++c) {
          const float w = set.weights[v][c];
          const size_t j = set.joints[v][c];
          if (w != 0.0f && j < joints.size()) xf += w * joints[j];
        }
      nx = normalMatrix(xf);
    }
    out.positions[v] = glm::vec3(xf * glm::vec4(out.positions[v], 1.0f));
    if (v < out.normals.size()) out.normals[v] = unit(nx * out.normals[v], m.normals[v]);
    if (v < out.tangents.size())
      out.tangents[v] =
          glm::vec4(unit(glm::mat3(xf) * glm::vec3(out.tangents[v]), glm::vec3(m.tangents[v])), m.tangents[v].w);
  }
  return out;
}

}  // namespace rgraph
