// The walker scene (loadSceneAny "walker", core/src/scene/procedural_walker.cpp)
// and posing a Scene on the CPU (rgraph/animation.h: PosedBounds, poseScene).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/animation.h"
#include "rgraph/scene.h"
#include "support/posed_bounds_check.h"

using namespace rgraph;

namespace {

// The largest distance a vertex of primitive `i` moves between two poses.
float largestMove(const Scene& s, size_t i, double t0, double t1) {
  const DeformedVertices a = deformPrimitive(s, evaluatePose(s.animation, t0, kAllAnimations), i);
  const DeformedVertices b = deformPrimitive(s, evaluatePose(s.animation, t1, kAllAnimations), i);
  float most = 0.0f;
  for (size_t v = 0; v < a.positions.size(); ++v) most = std::max(most, glm::distance(a.positions[v], b.positions[v]));
  return most;
}

}  // namespace

TEST(WalkerScene, ThreeSkinnedFiguresAndOneWalk) {
  const Scene s = loadSceneAny("walker");
  EXPECT_EQ(s.source, "walker");
  ASSERT_EQ(s.animation.animations.size(), 1u);
  EXPECT_EQ(s.animation.animations[0].name, "walk");
  EXPECT_DOUBLE_EQ(s.animation.animations[0].duration, 1.0);
  ASSERT_EQ(s.animation.skins.size(), 3u);
  EXPECT_EQ(s.animation.jointCount, 33u);
  size_t figures = 0;
  for (const Primitive& p : s.primitives) {
    const MeshData& m = s.meshes[size_t(p.mesh)];
    std::string why;
    EXPECT_TRUE(m.valid(&why)) << p.name << ": " << why;
    if (p.name.rfind("walker", 0) != 0) {
      EXPECT_EQ(p.node, -1) << p.name;  // the floor and the boxes stand still
      continue;
    }
    ++figures;
    ASSERT_GE(p.node, 0);
    const SceneNode& node = s.animation.nodes[size_t(p.node)];
    ASSERT_GE(node.skin, 0);
    const size_t joints = s.animation.skins[size_t(node.skin)].joints.size();
    EXPECT_EQ(joints, 11u);
    ASSERT_EQ(m.influences.size(), 1u);
    ASSERT_EQ(m.influences[0].joints.size(), m.vertexCount());
    ASSERT_EQ(m.influences[0].weights.size(), m.vertexCount());
    size_t blended = 0;
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec4 w = m.influences[0].weights[v];
      EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f);
      for (int k = 0; k < 4; ++k) EXPECT_LT(size_t(m.influences[0].joints[v][k]), joints);
      blended += w.y > 0.0f;
    }
    // Knees, elbows and the waist share their first ring with the parent joint.
    EXPECT_GT(blended, 0u);
  }
  EXPECT_EQ(figures, 3u);
  // At rest (every joint's rest transform) the skin draws the mesh where the
  // primitive's transform puts it: the inverse bind matrices undo the bind.
  const Pose rest = evaluatePose(s.animation, 0.0, kRestPose);
  for (size_t i = 0; i < s.primitives.size(); ++i) {
    if (s.primitives[i].node < 0) continue;
    const MeshData& m = s.meshes[size_t(s.primitives[i].mesh)];
    const DeformedVertices d = deformPrimitive(s, rest, i);
    float worst = 0.0f;
    for (size_t v = 0; v < m.vertexCount(); ++v)
      worst = std::max(worst, glm::distance(d.positions[v], glm::vec3(s.primitives[i].transform * glm::vec4(m.positions[v], 1.0f))));
    EXPECT_LT(worst, 1e-5f) << s.primitives[i].name;
  }
}

TEST(WalkerScene, TheWalkSwingsTheLimbsAndLoops) {
  const Scene s = loadSceneAny("walker");
  for (size_t i = 0; i < s.primitives.size(); ++i) {
    if (s.primitives[i].node < 0) continue;
    SCOPED_TRACE(s.primitives[i].name);
    // Half a stride apart the legs have swapped: feet move tens of centimetres
    // (whichever quarter of the stride each figure starts at).
    EXPECT_GT(std::max(largestMove(s, i, 0.0, 0.5), largestMove(s, i, 0.25, 0.75)), 0.5f);
    // One frame at 30 fps: a few centimetres (a few pixels in the bench's view).
    const float frame = largestMove(s, i, 0.2, 0.2 + 1.0 / 30.0);
    EXPECT_GT(frame, 0.01f);
    EXPECT_LT(frame, 0.15f);
    // The cycle closes: the end of the stride is its start.
    EXPECT_LT(largestMove(s, i, 0.0, 0.9999), 1e-3f);
    // The feet stay near the floor (y = 0) through the stride: never under it
    // by more than 3 cm, never lifted by more than 7 (a stride, not a hop).
    for (double t : {0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875}) {
      const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, t, kAllAnimations), i);
      float lowest = 1e9f;
      for (const glm::vec3& p : d.positions) lowest = std::min(lowest, p.y);
      EXPECT_GT(lowest, -0.03f) << "t = " << t;
      EXPECT_LT(lowest, 0.07f) << "t = " << t;
    }
  }
  // Out of step: the three figures are at different points of the stride.
  const Pose pose = evaluatePose(s.animation, 0.2, kAllAnimations);
  std::set<float> thighs;  // each left thigh's pitch, whole degrees
  for (size_t k = 0; k < s.animation.nodes.size(); ++k)
    if (s.animation.nodes[k].name.find("_thigh_l") != std::string::npos) {
      const glm::quat q = pose.rotation[k];
      thighs.insert(std::round(glm::degrees(2.0f * std::atan2(q.x, q.w))));
    }
  EXPECT_EQ(thighs.size(), 3u);
}

// poseScene gives every posed primitive bounds that hold its deformed
// vertices; without it the rest bounds miss the swinging limbs.
TEST(PoseScene, BoundsHoldTheWalk) {
  Scene s = loadSceneAny("walker");
  PosedBounds bounds;
  size_t restMisses = 0;
  for (double t : {0.1, 0.35, 0.6, 0.85}) {
    const Pose pose = evaluatePose(s.animation, t, kAllAnimations);
    restMisses += testsupport::verticesOutsideBounds(s, pose);  // still the previous (or rest) bounds
    poseScene(s, pose, bounds);
    EXPECT_EQ(testsupport::verticesOutsideBounds(s, pose), 0u) << "t = " << t;
  }
  EXPECT_GT(restMisses, 0u) << "the walk never left its previous bounds: the test shows nothing";
}

// A rigid animated node: poseScene gives its primitive the node's world
// matrix at the pose (a skinned one keeps its own: skinning ignores it).
TEST(PoseScene, RigidNodesTakeTheirWorldMatrix) {
  Scene s;
  s.meshes.push_back(makeCube(0.5f));
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.node = 0;
  p.bounds = p.worldBounds(s.meshes[0].bounds);
  s.primitives.push_back(p);
  s.animation.nodes.resize(1);
  Animation a;
  AnimationSampler slide;
  slide.components = 3;
  slide.times = {0.0f, 2.0f};
  slide.values = {0.0f, 0.0f, 0.0f, 4.0f, 0.0f, 0.0f};
  a.samplers.push_back(slide);
  a.channels.push_back({0, 0, AnimationPath::translation});
  a.duration = 2.0;
  s.animation.animations.push_back(a);
  s.animation.updateLayout();
  PosedBounds bounds;
  poseScene(s, evaluatePose(s.animation, 1.0, kAllAnimations), bounds);
  EXPECT_FLOAT_EQ(s.primitives[0].transform[3].x, 2.0f);
  EXPECT_NEAR(s.primitives[0].bounds.min.x, 1.5f, 1e-6f);
  EXPECT_NEAR(s.primitives[0].bounds.max.x, 2.5f, 1e-6f);
}
