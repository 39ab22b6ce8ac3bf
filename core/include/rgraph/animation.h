// glTF animation, skins and morph targets on the CPU (no GL): the data a
// loaded scene keeps (Scene::animation, MeshData::influences and
// MeshData::morphTargets, Primitive::node) and its exact evaluation at a time
// the caller gives: node matrices, joint matrices per skin, morph weights per
// node, and a reference deformer giving a primitive's vertices at that time.
//
// The arrays are laid out for upload as they are: a pose's joint matrices
// are one array of mat4 (skin s at SceneSkin::firstJoint), its morph weights
// one array of float (node n at SceneNode::firstWeight), a mesh's influences
// one uvec4/vec4 array per set of 4 and its morph deltas one vec3 array per
// target and attribute.
//
// The glTF rules followed (glTF 2.0, "Animations", "Skins", "Morph Targets"):
//   - a channel's value before its first key is the first key's, after its
//     last the last key's; STEP holds a key until the next; LINEAR lerps
//     translation, scale and weights and slerps rotation along the shortest
//     arc; CUBICSPLINE is the Hermite spline of each key's (in-tangent,
//     value, out-tangent), tangents scaled by the key interval; rotations
//     are normalized after interpolation;
//   - a node's local matrix is T * R * S (or its matrix; such nodes cannot
//     be animated), its world matrix the parent's world times it;
//   - joint matrix i of a skin = world(joints[i]) * inverseBindMatrices[i]:
//     a skinned vertex is sum_k w_k * jointMatrix(j_k) * v in world space,
//     the skinned node's own transform is ignored;
//   - morphed attribute = base + sum_i weights[i] * delta_i, with the node's
//     weights (animated, else the node's "weights", else the mesh's, else 0).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace rgraph {

struct Scene;
struct Primitive;
struct Bounds;

// ---------------------------------------------------------------- per vertex

// One set of 4 skin influences per vertex (glTF JOINTS_n / WEIGHTS_n): joint
// indices into the drawing node's skin and their weights (normalized
// integers already turned into [0, 1]; not renormalized).
struct SkinInfluences {
  std::vector<glm::u16vec4> joints;
  std::vector<glm::vec4> weights;
};

// A morph target's per-vertex displacements (glTF targets[i]): each empty or
// one per vertex of its mesh. `tangents` displace tangent.xyz (w is kept).
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;
};

// ---------------------------------------------------------------- scene data

// One glTF node, kept so that animated scenes can be evaluated.
struct SceneNode {
  std::string name;
  int parent = -1;  // index into SceneAnimation::nodes; -1: a root
  // Roots: what stands above the file's hierarchy (identity; a scene file's
  // model transform). world(root) = rootTransform * local(root).
  glm::mat4 rootTransform{1.0f};
  // The rest transform: `matrix` when hasMatrix (never animated: glTF forbids
  // animating a node given by matrix), else translation * rotation * scale.
  bool hasMatrix = false;
  glm::mat4 matrix{1.0f};
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // unit (w, x, y, z)
  glm::vec3 scale{1.0f};
  int skin = -1;  // index into SceneAnimation::skins: the node's mesh is skinned by it
  // Rest morph weights of the node's mesh (the node's "weights", else the
  // mesh's, else zeros); empty: its mesh has no morph targets.
  std::vector<float> weights;
  uint32_t firstWeight = 0;  // where its weights start in Pose::weights

  glm::mat4 restMatrix() const;
};

struct SceneSkin {
  std::string name;
  std::vector<int> joints;                     // node indices
  std::vector<glm::mat4> inverseBindMatrices;  // one per joint (identity where the file has none)
  int skeleton = -1;                           // the file's "skeleton" node (informative: joints carry the hierarchy)
  uint32_t firstJoint = 0;                     // where its joint matrices start in Pose::joints
};

enum class AnimationPath : uint8_t { translation, rotation, scale, weights };
enum class Interpolation : uint8_t { step, linear, cubicSpline };
const char* interpolationName(Interpolation i);

struct AnimationSampler {
  Interpolation interpolation = Interpolation::linear;
  std::vector<float> times;  // seconds, finite, >= 0, strictly increasing
  // `components` floats per key (3 translation/scale, 4 rotation x,y,z,w,
  // the target count for weights); cubicSpline: 3 such groups per key
  // (in-tangent, value, out-tangent).
  std::vector<float> values;
  uint32_t components = 0;
};

struct AnimationChannel {
  int sampler = -1;  // index into Animation::samplers
  int node = -1;     // index into SceneAnimation::nodes
  AnimationPath path = AnimationPath::translation;
};

struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;
  double duration = 0.0;  // the last key time over its samplers (seconds)
};

// Everything evaluation needs. Empty (no nodes) for a scene without
// animations, skins and morph targets: its Primitive::transform is final.
struct SceneAnimation {
  std::vector<SceneNode> nodes;
  std::vector<int> order;  // every node once, parents before children
  std::vector<SceneSkin> skins;
  std::vector<Animation> animations;
  uint32_t jointCount = 0;   // over all skins (Pose::joints' size)
  uint32_t weightCount = 0;  // over all nodes (Pose::weights' size)

  bool empty() const { return nodes.empty(); }
  // Recomputes order, firstJoint, firstWeight and the counts (after editing
  // or appending nodes and skins).
  void updateLayout();
};

// Appends `src`'s nodes, skins and animations to `dst` (appendScene):
// indices rebased, `transform` put above src's roots.
void appendAnimation(SceneAnimation& dst, SceneAnimation src, const glm::mat4& transform);

// ---------------------------------------------------------------- evaluation

// Which animation a pose plays.
inline constexpr int kRestPose = -1;       // none: every node at rest
inline constexpr int kAllAnimations = -2;  // every animation at once, each looping on its own duration
                                           // (a scene file's several models); a later one wins on a shared target

struct Pose {
  // Per node: its translation, rotation and scale at this time (the rest
  // values where no channel drives them; a node given by matrix keeps the
  // defaults here and its matrix in `local`).
  std::vector<glm::vec3> translation;
  std::vector<glm::quat> rotation;
  std::vector<glm::vec3> scale;
  std::vector<glm::mat4> local;   // per node
  std::vector<glm::mat4> world;   // per node
  std::vector<glm::mat4> joints;  // all skins' joint matrices (skin s from SceneSkin::firstJoint)
  std::vector<float> weights;     // all nodes' morph weights (node n from SceneNode::firstWeight)

  std::span<const glm::mat4> skinJoints(const SceneAnimation& a, int skin) const;
  std::span<const float> nodeWeights(const SceneAnimation& a, int node) const;
};

// The time within an animation of duration `duration` at the caller's clock
// `seconds`: animations loop (as glTF viewers play them), so seconds modulo
// the duration, in [0, duration); 0 for a duration of 0. Negative clocks
// wrap the same way (-0.25 s of a 2 s clip is 1.75 s).
double loopTime(double seconds, double duration);

// One sampler's value at animation time `t` (not looped here) into out
// (`components` floats). Rotations (`rotation` true) slerp and come out
// normalized.
void sampleAnimation(const AnimationSampler& s, double t, bool rotation, float* out);

// The pose at the caller's clock `seconds` playing animation `animation` (an
// index, kRestPose or kAllAnimations), into `out` (its vectors are reused:
// no allocation once sized). Throws RuntimeError when the index names no
// animation.
void evaluatePose(const SceneAnimation& a, double seconds, int animation, Pose& out);
Pose evaluatePose(const SceneAnimation& a, double seconds, int animation = 0);

// Where a primitive's vertices lie at a pose (culling, sorting and shadow
// fitting read Primitive::bounds): the mesh's local box widened by its node's
// morph weights (each target's box of position deltas times its weight),
// then, skinned (its node has a skin and its mesh influences), the union of
// that box under every joint matrix of the skin (a skinned vertex is a
// weighted mean of its joints' images of it), else that box under the
// primitive's transform and instances. Keeps each mesh's target boxes, made
// at the first use.
class PosedBounds {
 public:
  Bounds operator()(const Scene& scene, const Pose& pose, const Primitive& primitive);

 private:
  std::vector<std::vector<Bounds>> targetBounds_;  // per mesh, per target
};

// Poses `scene` as a renderer does when the caller edits nothing: each
// primitive of an animated node takes its node's world matrix (skinned ones
// keep theirs: skinning ignores it) and bounds that hold the pose. (The
// GPU copy gets pose.joints and pose.weights through GpuScene::setPose.)
void poseScene(Scene& scene, const Pose& pose, PosedBounds& bounds);

// A primitive's vertices at a pose, in world space: the reference the GPU
// path is compared with. Morph targets first (the node's weights), then the
// skin (sum of weighted joint matrices; normals by the inverse transpose of
// that sum, renormalized) or, unskinned, the node's world matrix (a
// primitive without a node: Primitive::transform). EXT_mesh_gpu_instancing
// instances are not applied (the node's own placement only). Tangents are
// given when the mesh has them (xyz deformed like normals' tangent plane:
// by the matrix itself, renormalized; w kept).
struct DeformedVertices {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
};
DeformedVertices deformPrimitive(const Scene& scene, const Pose& pose, size_t primitive);

}  // namespace rgraph
