// The walker scene (loadSceneAny "walker"): skinned figures on a walk cycle,
// what the bench's aa axis measures TAA on when the motion is skinning and
// not the camera or whole objects. The figures are built as a glTF exporter
// would leave them: joints are nodes, the mesh lies in the bind pose with
// 2 influences per vertex where a limb meets its parent, inverse bind
// matrices undo each joint's bind placement, and one animation drives every
// joint's rotation with LINEAR keys (rgraph/animation.h evaluates it).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "procedural_internal.h"
#include "rgraph/animation.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

// One joint of the figure: its parent (-1: the hips, the root), where it
// sits in its parent's frame at rest, and the limb drawn from it: a tube to
// `end` (in its own frame) with radii at both ends. `blend`: the tube's first
// ring is shared half with the parent joint (a knee or an elbow bends
// smoothly; a limb that starts inside the torso needs none).
struct JointDef {
  const char* name;
  int parent;
  glm::vec3 offset;
  glm::vec3 end;
  float radiusStart, radiusEnd;
  bool blend;
};

enum Joint { hips, spine, head, thighL, shinL, thighR, shinR, armL, forearmL, armR, forearmR, kJoints };

// A figure 1.8 high facing +z, feet at y = 0.
const std::array<JointDef, kJoints> kSkeleton = {{
    {"hips", -1, {0.0f, 0.92f, 0.0f}, {0.0f, 0.12f, 0.0f}, 0.15f, 0.14f, false},
    {"spine", hips, {0.0f, 0.1f, 0.0f}, {0.0f, 0.5f, 0.0f}, 0.14f, 0.17f, true},
    {"head", spine, {0.0f, 0.55f, 0.0f}, {0.0f, 0.24f, 0.0f}, 0.1f, 0.1f, false},
    {"thigh_l", hips, {0.1f, -0.03f, 0.0f}, {0.0f, -0.44f, 0.0f}, 0.075f, 0.06f, false},
    {"shin_l", thighL, {0.0f, -0.44f, 0.0f}, {0.0f, -0.46f, 0.0f}, 0.06f, 0.045f, true},
    {"thigh_r", hips, {-0.1f, -0.03f, 0.0f}, {0.0f, -0.44f, 0.0f}, 0.075f, 0.06f, false},
    {"shin_r", thighR, {0.0f, -0.44f, 0.0f}, {0.0f, -0.46f, 0.0f}, 0.06f, 0.045f, true},
    {"arm_l", spine, {0.21f, 0.48f, 0.0f}, {0.0f, -0.3f, 0.0f}, 0.05f, 0.045f, false},
    {"forearm_l", armL, {0.0f, -0.3f, 0.0f}, {0.0f, -0.28f, 0.0f}, 0.045f, 0.035f, true},
    {"arm_r", spine, {-0.21f, 0.48f, 0.0f}, {0.0f, -0.3f, 0.0f}, 0.05f, 0.045f, false},
    {"forearm_r", armR, {0.0f, -0.3f, 0.0f}, {0.0f, -0.28f, 0.0f}, 0.045f, 0.035f, true},
}};

constexpr int kTubeSides = 10, kTubeRings = 6;

// Appends joint j's tube (in the figure's bind space: from `start` along
// `axis` with length `length`) to `m`, closed at both ends.
void addTube(MeshData& m, int j, glm::vec3 start, glm::vec3 axis, float length) {
  const JointDef& d = kSkeleton[size_t(j)];
  const glm::vec3 dir = axis / length;
  // A frame around the axis (the axis is never parallel to z here).
  const glm::vec3 u = glm::normalize(glm::cross(dir, glm::vec3(0.0f, 0.0f, 1.0f)));
  const glm::vec3 v = glm::cross(dir, u);
  SkinInfluences& inf = m.influences.front();
  auto vertex = [&](glm::vec3 p, glm::vec3 n, glm::vec2 uv, float parentWeight) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    m.uv0.push_back(uv);
    const uint16_t own = uint16_t(j), parent = uint16_t(d.parent < 0 ? j : d.parent);
    inf.joints.push_back({own, parent, 0, 0});
    inf.weights.push_back({1.0f - parentWeight, parentWeight, 0.0f, 0.0f});
    return uint32_t(m.positions.size() - 1);
  };
  const uint32_t first = uint32_t(m.positions.size());
  for (int r = 0; r < kTubeRings; ++r) {
    const float f = float(r) / float(kTubeRings - 1);
    const float radius = glm::mix(d.radiusStart, d.radiusEnd, f);
    const float parentWeight = d.blend && r == 0 ? 0.5f : 0.0f;
    for (int k = 0; k < kTubeSides; ++k) {
      const float a = glm::two_pi<float>() * float(k) / float(kTubeSides);
      const glm::vec3 n = std::cos(a) * u + std::sin(a) * v;
      vertex(start + axis * f + radius * n, n, {float(k) / float(kTubeSides), f}, parentWeight);
    }
  }
  for (int r = 0; r + 1 < kTubeRings; ++r)
    for (int k = 0; k < kTubeSides; ++k) {
      const uint32_t a = first + uint32_t(r * kTubeSides + k), b = first + uint32_t(r * kTubeSides + (k + 1) % kTubeSides);
      const uint32_t c = a + kTubeSides, e = b + kTubeSides;
      // Counter-clockwise seen from outside (u, v, dir is right-handed).
      m.indices.insert(m.indices.end(), {a, e, c, a, b, e});
    }
  // Caps: a fan around each end's centre, facing out along the axis.
  for (int end = 0; end < 2; ++end) {
    const float radius = end == 0 ? d.radiusStart : d.radiusEnd;
    const glm::vec3 n = end == 0 ? -dir : dir;
    const glm::vec3 centre = start + (end == 0 ? glm::vec3(0.0f) : axis);
    const float parentWeight = d.blend && end == 0 ? 0.5f : 0.0f;
    const uint32_t c = vertex(centre, n, {0.5f, float(end)}, parentWeight);
    const uint32_t rim = uint32_t(m.positions.size());
    for (int k = 0; k < kTubeSides; ++k) {
      const float a = glm::two_pi<float>() * float(k) / float(kTubeSides);
      const glm::vec3 offset = std::cos(a) * u + std::sin(a) * v;
      vertex(centre + radius * offset, n, {0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)}, parentWeight);
    }
    for (int k = 0; k < kTubeSides; ++k) {
      const uint32_t a = rim + uint32_t(k), b = rim + uint32_t((k + 1) % kTubeSides);
      if (end == 0)
        m.indices.insert(m.indices.end(), {c, b, a});
      else
        m.indices.insert(m.indices.end(), {c, a, b});
    }
  }
}

// Each joint's bind placement in the figure's frame (parents come first in kSkeleton).
std::array<glm::mat4, kJoints> bindPlacements() {
  std::array<glm::mat4, kJoints> bind{};
  for (size_t j = 0; j < kJoints; ++j) {
    const glm::mat4 local = glm::translate(glm::mat4(1.0f), kSkeleton[j].offset);
    bind[j] = kSkeleton[j].parent < 0 ? local : bind[size_t(kSkeleton[j].parent)] * local;
  }
  return bind;
}

// The figure's skinned mesh in bind space: one tube per joint.
MeshData makeFigureMesh() {
  MeshData m;
  m.name = "walker";
  m.hasUv0 = true;
  m.influences.resize(1);
  const std::array<glm::mat4, kJoints> bind = bindPlacements();
  for (int j = 0; j < kJoints; ++j) {
    const glm::vec3 start(bind[size_t(j)][3]);
    addTube(m, j, start, kSkeleton[size_t(j)].end, glm::length(kSkeleton[size_t(j)].end));
  }
  m.updateBounds();
  return m;
}

// The walk: a 1-second stride cycle at `phase` (a fraction of the cycle),
// each joint's rotation about its x axis (pitch, degrees; forward swing is
// negative) at time fraction t, and the hips' height.
float pitchAt(int joint, float t) {
  const float s = std::sin(glm::two_pi<float>() * t);
  switch (joint) {
    case thighL: return -28.0f * s;
    case thighR: return 28.0f * s;
    // The knee bends while its leg swings forward (sin > 0 for the left leg).
    case shinL: return 8.0f + 45.0f * std::max(0.0f, std::sin(glm::two_pi<float>() * t + 0.6f));
    case shinR: return 8.0f + 45.0f * std::max(0.0f, -std::sin(glm::two_pi<float>() * t + 0.6f));
    case armL: return 24.0f * s;  // opposite to its leg
    case armR: return -24.0f * s;
    case forearmL: return -18.0f - 14.0f * std::max(0.0f, -s);
    case forearmR: return -18.0f - 14.0f * std::max(0.0f, s);
    case spine: return -4.0f;  // leaning into the walk
    default: return 0.0f;
  }
}

constexpr int kWalkKeys = 17;  // over one cycle, both ends included (the loop is seamless)

// Appends one figure (joints, skinned body node, the walk's channels at
// `phase`) to `s`, standing at `placement`.
void addFigure(Scene& s, int mesh, int material, const glm::mat4& placement, float phase, const std::string& name) {
  SceneAnimation& a = s.animation;
  Animation& walk = a.animations.front();
  const int base = int(a.nodes.size());
  const std::array<glm::mat4, kJoints> bind = bindPlacements();
  SceneSkin skin;
  skin.name = name;
  skin.skeleton = base + hips;
  for (int j = 0; j < kJoints; ++j) {
    const JointDef& d = kSkeleton[size_t(j)];
    SceneNode n;
    n.name = name + "_" + d.name;
    n.parent = d.parent < 0 ? -1 : base + d.parent;
    if (d.parent < 0) n.rootTransform = placement;
    n.translation = d.offset;
    a.nodes.push_back(n);
    skin.joints.push_back(base + j);
    skin.inverseBindMatrices.push_back(glm::inverse(bind[size_t(j)]));

    AnimationSampler rotation;
    rotation.interpolation = Interpolation::linear;
    rotation.components = 4;
    for (int k = 0; k < kWalkKeys; ++k) {
      const float t = float(k) / float(kWalkKeys - 1);
      const glm::quat q = glm::angleAxis(glm::radians(pitchAt(j, t + phase)), glm::vec3(1.0f, 0.0f, 0.0f));
      rotation.times.push_back(t);
      rotation.values.insert(rotation.values.end(), {q.x, q.y, q.z, q.w});
    }
    walk.samplers.push_back(std::move(rotation));
    walk.channels.push_back({int(walk.samplers.size()) - 1, base + j, AnimationPath::rotation});
  }
  // The hips bob twice per stride (lowest as the feet pass each other).
  AnimationSampler bob;
  bob.interpolation = Interpolation::linear;
  bob.components = 3;
  for (int k = 0; k < kWalkKeys; ++k) {
    const float t = float(k) / float(kWalkKeys - 1);
    const glm::vec3 p = kSkeleton[hips].offset + glm::vec3(0.0f, 0.02f * std::cos(2.0f * glm::two_pi<float>() * (t + phase)), 0.0f);
    bob.times.push_back(t);
    bob.values.insert(bob.values.end(), {p.x, p.y, p.z});
  }
  walk.samplers.push_back(std::move(bob));
  walk.channels.push_back({int(walk.samplers.size()) - 1, base + hips, AnimationPath::translation});
  walk.duration = 1.0;

  // The node that draws the body: a root whose own transform skinning
  // ignores (glTF), given the placement so that the rest draw stands there.
  SceneNode body;
  body.name = name;
  body.rootTransform = placement;
  body.skin = int(a.skins.size());
  a.nodes.push_back(body);
  a.skins.push_back(std::move(skin));
  addDraw(s, mesh, material, placement, name);
  s.primitives.back().node = int(a.nodes.size()) - 1;
}

}  // namespace

Scene makeWalkerScene() {
  Scene s;
  s.source = "walker";
  s.meshes.push_back(makeFigureMesh());               // mesh 0: the figure, skinned
  s.meshes.push_back(makePlane(8.0f, 8.0f, 1.0f));    // mesh 1: the floor
  s.meshes.push_back(makeCube(1.0f));                 // mesh 2: the backdrop's boxes
  auto material = [&](const std::string& name, glm::vec3 color, float specular) {
    return addFlatMaterial(s, name, color, specular, 0.6f);
  };
  const int floorMat = material("floor", {0.2f, 0.2f, 0.22f}, 0.1f);
  const int wallMat = material("wall", {0.45f, 0.5f, 0.55f}, 0.2f);
  const int figureMat[3] = {material("walker_red", {0.85f, 0.3f, 0.25f}, 0.4f),
                            material("walker_green", {0.35f, 0.8f, 0.35f}, 0.4f),
                            material("walker_blue", {0.3f, 0.45f, 0.9f}, 0.4f)};
  addDraw(s, 1, floorMat, glm::mat4(1.0f), "floor");
  // A backdrop of tall boxes: bright edges behind the limbs (disocclusion).
  for (int i = 0; i < 5; ++i) {
    const glm::mat4 xf = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 1.5f * float(i), 1.0f, -2.5f)),
                                    glm::vec3(0.3f, 1.0f, 0.3f));
    addDraw(s, 2, wallMat, xf, "pillar" + std::to_string(i));
  }

  s.animation.animations.resize(1);
  s.animation.animations.front().name = "walk";
  // Three figures side-on to the camera (the legs swing across the view),
  // out of step with each other.
  const float yaw[3] = {90.0f, 70.0f, 110.0f};
  for (int i = 0; i < 3; ++i) {
    const glm::mat4 placement =
        glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-1.3f + 1.3f * float(i), 0.0f, 0.2f * float(i % 2))),
                    glm::radians(yaw[i]), glm::vec3(0.0f, 1.0f, 0.0f));
    addFigure(s, 0, figureMat[i], placement, 0.3f * float(i), "walker" + std::to_string(i));
  }
  s.animation.updateLayout();

  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.6f));
  sun.color = glm::vec3(1.0f, 0.97f, 0.92f);
  sun.intensity = 0.9f;
  s.directionalLights.push_back(sun);
  addFalloffLights(s, {{-2.5f, 2.0f, 2.0f}, {0.0f, 2.5f, 3.0f}, {2.5f, 2.0f, 2.0f}},
                   {{1.0f, 0.7f, 0.5f}, {0.7f, 0.8f, 1.0f}, {0.8f, 1.0f, 0.7f}});
  s.ambient = glm::vec3(0.1f);
  placeCamera(s, {0.0f, 1.3f, 4.6f}, {0.0f, 0.9f, 0.0f}, 40.0f);
  return s;
}

}  // namespace rgraph
