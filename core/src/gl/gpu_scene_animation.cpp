// GpuScene's skins and morph targets (rgraph/gl/gpu_scene.h): the upload of
// influences and morph deltas, the pose buffers (this frame's and the
// previous frame's joint matrices and morph weights) and the per-draw
// uniforms scene.vert's SCENE_ANIMATION code reads.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/scene.h"

namespace rgraph {
namespace {

// std430 mirror of scene.vert's SkinInfluence.
struct GpuInfluence {
  glm::uvec4 joints;
  glm::vec4 weights;
};
static_assert(sizeof(GpuInfluence) == 32, "GpuInfluence must match the std430 layout");

// A storage buffer of `bytes` (at least 16: an empty binding is an error),
// holding `data` when given (the pose buffers are written per frame).
gl::Buffer storageBuffer(const void* data, size_t bytes) {
  gl::Buffer b = gl::createBuffer();
  glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(std::max<size_t>(bytes, 16)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (bytes && data) glNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(bytes), data);
  return b;
}

// Writes the one range of `next` that differs from `gpu` (all of it when
// `gpu` has another size) into `buffer`; returns the bytes written.
template <class T>
uint64_t writeChanged(const gl::Buffer& buffer, std::vector<T>& gpu, const std::vector<T>& next) {
  size_t first = next.size(), last = 0;
  for (size_t i = 0; i < next.size(); ++i)
    if (gpu.size() != next.size() || std::memcmp(&gpu[i], &next[i], sizeof(T)) != 0) {
      first = std::min(first, i);
      last = i + 1;
    }
  gpu = next;
  if (first >= last) return 0;
  const size_t bytes = (last - first) * sizeof(T);
  glNamedBufferSubData(buffer.id(), static_cast<GLintptr>(first * sizeof(T)), static_cast<GLsizeiptr>(bytes),
                       &next[first]);
  return bytes;
}

}  // namespace

bool GpuScene::sceneDeforms(const Scene& scene) {
  const SceneAnimation& a = scene.animation;
  for (const Primitive& p : scene.primitives) {
    if (p.node < 0 || size_t(p.node) >= a.nodes.size() || p.mesh < 0 || size_t(p.mesh) >= scene.meshes.size())
      continue;
    const SceneNode& n = a.nodes[size_t(p.node)];
    const MeshData& m = scene.meshes[size_t(p.mesh)];
    if ((n.skin >= 0 && m.skinned()) || (!n.weights.empty() && !m.morphTargets.empty())) return true;
  }
  return false;
}

void GpuScene::uploadDeformation() {
  deforms_ = sceneDeforms(scene_);
  if (!deforms_) return;
  const SceneAnimation& a = scene_.animation;
  // Which meshes some primitive skins or morphs (the others upload nothing).
  std::vector<bool> skinned(scene_.meshes.size(), false), morphed(scene_.meshes.size(), false);
  for (const Primitive& p : scene_.primitives) {
    if (p.node < 0 || size_t(p.node) >= a.nodes.size()) continue;
    const MeshData& m = scene_.meshes[size_t(p.mesh)];
    if (a.nodes[size_t(p.node)].skin >= 0 && m.skinned()) skinned[size_t(p.mesh)] = true;
    if (!a.nodes[size_t(p.node)].weights.empty() && !m.morphTargets.empty()) morphed[size_t(p.mesh)] = true;
  }
  std::vector<GpuInfluence> influences;
  std::vector<glm::vec4> deltas;
  for (size_t i = 0; i < scene_.meshes.size() && i < meshes_.size(); ++i) {
    const MeshData& m = scene_.meshes[i];
    GpuMesh& g = meshes_[i];
    const size_t n = m.vertexCount();
    if (skinned[i]) {
      g.firstInfluence = static_cast<int32_t>(influences.size());
      g.influenceSets = static_cast<int32_t>(m.influences.size());
      for (size_t v = 0; v < n; ++v)
        for (const SkinInfluences& set : m.influences)
          influences.push_back({glm::uvec4(set.joints[v]), set.weights[v]});
    }
    if (morphed[i]) {
      // The attributes any target displaces; a target without one adds zeros.
      int bits = 0;
      for (const MorphTarget& t : m.morphTargets)
        bits |= (t.positions.empty() ? 0 : 1) | (t.normals.empty() ? 0 : 2) | (t.tangents.empty() ? 0 : 4);
      g.firstDelta = static_cast<int32_t>(deltas.size());
      g.morphTargets = static_cast<int32_t>(m.morphTargets.size());
      g.morphAttributes = bits;
      auto push = [&](const std::vector<glm::vec3>& d, size_t v) {
        deltas.push_back(glm::vec4(d.empty() ? glm::vec3(0.0f) : d[v], 0.0f));
      };
      for (size_t v = 0; v < n; ++v)
        for (const MorphTarget& t : m.morphTargets) {
          if (bits & 1) push(t.positions, v);
          if (bits & 2) push(t.normals, v);
          if (bits & 4) push(t.tangents, v);
        }
    }
  }
  influences_ = storageBuffer(influences.data(), influences.size() * sizeof(GpuInfluence));
  morphDeltas_ = storageBuffer(deltas.data(), deltas.size() * sizeof(glm::vec4));
  deformationBytes_ = influences.size() * sizeof(GpuInfluence) + deltas.size() * sizeof(glm::vec4);
  geometryBytes_ += deformationBytes_;
  jointCount_ = a.jointCount;
  weightCount_ = a.weightCount;
  joints_ = storageBuffer(nullptr, 2 * size_t(jointCount_) * sizeof(glm::mat4));
  morphWeights_ = storageBuffer(nullptr, 2 * size_t(weightCount_) * sizeof(float));
  const Pose rest = evaluatePose(a, 0.0, kRestPose);
  pose_ = rest.joints;
  poseWeights_ = rest.weights;
}

void GpuScene::setPose(const std::vector<glm::mat4>& joints, const std::vector<float>& weights) {
  if (!deforms_) return;
  if (joints.size() != jointCount_ || weights.size() != weightCount_)
    throw RuntimeError("GpuScene::setPose: " + std::to_string(joints.size()) + " joints and " +
                       std::to_string(weights.size()) + " weights for a scene of " + std::to_string(jointCount_) +
                       " and " + std::to_string(weightCount_));
  pose_ = joints;
  poseWeights_ = weights;
}

void GpuScene::writePose(std::optional<uint64_t> frame, bool cut) {
  if (!deforms_) return;
  // The previous frame's pose: the one drawn last frame when this frame
  // follows it; kept when the same frame is drawn again (a second renderer);
  // else this frame's (no motion: first frame, camera cut, frames skipped).
  std::vector<glm::mat4> joints(2 * size_t(jointCount_));
  std::vector<float> weights(2 * size_t(weightCount_));
  std::copy(pose_.begin(), pose_.end(), joints.begin());
  std::copy(poseWeights_.begin(), poseWeights_.end(), weights.begin());
  const bool follows = frame && !cut && poseFrame_ && gpuJoints_.size() == joints.size() &&
                       gpuWeights_.size() == weights.size() && (*poseFrame_ + 1 == *frame || *poseFrame_ == *frame);
  const size_t fromJoint = follows && *poseFrame_ == *frame ? jointCount_ : 0;  // the same frame: its previous
  const size_t fromWeight = follows && *poseFrame_ == *frame ? weightCount_ : 0;
  if (follows) {
    std::copy(gpuJoints_.begin() + std::ptrdiff_t(fromJoint), gpuJoints_.begin() + std::ptrdiff_t(fromJoint + jointCount_),
              joints.begin() + jointCount_);
    std::copy(gpuWeights_.begin() + std::ptrdiff_t(fromWeight),
              gpuWeights_.begin() + std::ptrdiff_t(fromWeight + weightCount_), weights.begin() + weightCount_);
  } else {
    std::copy(pose_.begin(), pose_.end(), joints.begin() + jointCount_);
    std::copy(poseWeights_.begin(), poseWeights_.end(), weights.begin() + weightCount_);
  }
  poseFrame_ = frame;
  poseBytes_ += writeChanged(joints_, gpuJoints_, joints);
  poseBytes_ += writeChanged(morphWeights_, gpuWeights_, weights);
}

void GpuScene::bindDeformation(uint32_t program, int poseStrideLocation) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kJointBinding, joints_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMorphWeightBinding, morphWeights_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInfluenceBinding, influences_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMorphDeltaBinding, morphDeltas_.id());
  glProgramUniform2i(program, poseStrideLocation, static_cast<GLint>(jointCount_), static_cast<GLint>(weightCount_));
}

void GpuScene::setDeformation(uint32_t program, int skinLocation, int morphLocation, size_t primitive) const {
  const Primitive& p = scene_.primitives[primitive];
  const GpuMesh& g = meshes_[size_t(p.mesh)];
  const SceneAnimation& a = scene_.animation;
  glm::ivec4 skin(0), morph(0);
  if (p.node >= 0 && size_t(p.node) < a.nodes.size()) {
    const SceneNode& n = a.nodes[size_t(p.node)];
    if (n.skin >= 0 && g.influenceSets > 0)
      skin = {g.firstInfluence, g.influenceSets, static_cast<int>(a.skins[size_t(n.skin)].firstJoint), 0};
    // (The loader gives the node one weight per target of its mesh.)
    if (g.morphTargets > 0 && n.weights.size() == size_t(g.morphTargets))
      morph = {g.firstDelta, g.morphTargets, static_cast<int>(n.firstWeight), g.morphAttributes};
  }
  if (skinLocation >= 0) glProgramUniform4i(program, skinLocation, skin.x, skin.y, skin.z, skin.w);
  if (morphLocation >= 0) glProgramUniform4i(program, morphLocation, morph.x, morph.y, morph.z, morph.w);
  drawUniformBytes_ += 2 * sizeof(glm::ivec4);
}

void GpuScene::unbindDeformation() const {
  for (uint32_t b : {kJointBinding, kMorphWeightBinding, kInfluenceBinding, kMorphDeltaBinding})
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
}

}  // namespace rgraph
