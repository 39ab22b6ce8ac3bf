// STEP, LINEAR and CUBICSPLINE samplers, several influence sets, morph
// normals and tangents, and the choice of animation, on small glTF files
// built in memory (gltf_animation_rig.h); expected values are worked out by
// hand in the comments from the keys the tests write.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gltf_animation_rig.h"
#include "rgraph/animation.h"
#include "rgraph/scene.h"

using namespace rgraph;
using animtest::GltfBuilder;
using animtest::rig;

namespace {

constexpr float kTol = 1e-5f;  // float rounding of a few products

glm::vec3 translationAt(const Scene& s, int node, double t, int animation = 0) {
  return evaluatePose(s.animation, t, animation).translation[size_t(node)];
}

}  // namespace

// STEP holds key k's value over [t_k, t_k+1): keys 0, 1, 2 s at x = 0, 1, 5.
// Fails when STEP interpolates (t = 0.5 would give 0.5).
TEST(GltfAnimationInterpolation, StepHoldsEachKey) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "STEP", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 5, 0, 0}, "VEC3", 3);
  const Scene s = b.load();
  EXPECT_EQ(s.animation.animations[0].samplers[0].interpolation, Interpolation::step);
  EXPECT_NEAR(translationAt(s, 2, 0.5).x, 0.0f, kTol);
  EXPECT_NEAR(translationAt(s, 2, 0.999).x, 0.0f, kTol);
  EXPECT_NEAR(translationAt(s, 2, 1.0).x, 1.0f, kTol);
  EXPECT_NEAR(translationAt(s, 2, 1.5).x, 1.0f, kTol);
  EXPECT_NEAR(translationAt(s, 2, 1.999).x, 1.0f, kTol);
}

// LINEAR translation and scale: a straight line between keys.
TEST(GltfAnimationInterpolation, LinearTranslationAndScale) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "LINEAR", {0, 1, 2}, {0, 0, 0, 1, 0, 0, 5, 0, 0}, "VEC3", 3);
  b.animate(1, "scale", "LINEAR", {0, 1}, {1, 1, 1, 3, 1, 1}, "VEC3", 2);
  const Scene s = b.load();
  EXPECT_NEAR(translationAt(s, 2, 0.25).x, 0.25f, kTol);
  EXPECT_NEAR(translationAt(s, 2, 1.5).x, 3.0f, kTol);  // halfway from 1 to 5
  const Pose p = evaluatePose(s.animation, 0.5, 1);
  EXPECT_NEAR(p.scale[1].x, 2.0f, kTol);
  EXPECT_NEAR(p.world[1][0][0], 2.0f, kTol);
  // Node 2 (child of the scaled node 1) inherits: world x axis doubled.
  EXPECT_NEAR(p.world[2][0][0], 2.0f, kTol);
}

// CUBICSPLINE translation, keys at 0 and 2 s (td = 2), each key stored as
// (in-tangent, value, out-tangent):
//   key 0: in (9,9,9) (unused), value (0,0,0), out (1,1,0)
//   key 1: in (0,2,0),          value (1,1,0), out (9,9,9) (unused)
// p(u) = h00 v0 + td h10 b0 + h01 v1 + td h11 a1, u = (t - t0) / td, with
// h00 = 2u^3-3u^2+1, h10 = u^3-2u^2+u, h01 = -2u^3+3u^2, h11 = u^3-u^2.
//   t = 1 (u = 1/2):   h = (1/2, 1/8, 1/2, -1/8): x = 2/8 + 1/2 = 0.75,  y = 0.75 - 2*2/8 = 0.25
//   t = 0.5 (u = 1/4): h = (27/32, 9/64, 5/32, -3/64): x = 18/64 + 5/32 = 0.4375, y = 0.4375 - 12/64 = 0.25
// Fails without the key-interval scaling of the tangents (x = 0.625 at t = 1)
// or with the tangents read from the wrong slots.
TEST(GltfAnimationInterpolation, CubicSplineTranslation) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "CUBICSPLINE", {0, 2}, {9, 9, 9, 0, 0, 0, 1, 1, 0, 0, 2, 0, 1, 1, 0, 9, 9, 9}, "VEC3", 6);
  b.animate(1, "scale", "LINEAR", {0, 4}, {1, 1, 1, 1, 1, 1}, "VEC3", 2);  // lengthens a second animation
  const Scene s = b.load();
  EXPECT_EQ(s.animation.animations[0].samplers[0].interpolation, Interpolation::cubicSpline);
  const glm::vec3 at1 = translationAt(s, 2, 1.0), atHalf = translationAt(s, 2, 0.5);
  EXPECT_NEAR(at1.x, 0.75f, kTol);
  EXPECT_NEAR(at1.y, 0.25f, kTol);
  EXPECT_NEAR(atHalf.x, 0.4375f, kTol);
  EXPECT_NEAR(atHalf.y, 0.25f, kTol);
  // Keys themselves: the values, not the tangents.
  EXPECT_NEAR(translationAt(s, 2, 0.0).x, 0.0f, kTol);
  // Both animations at once (kAllAnimations): each loops on its own
  // duration; at 3 s the 2 s translation is at 1 s again.
  const glm::vec3 all = translationAt(s, 2, 3.0, kAllAnimations);
  EXPECT_NEAR(all.x, 0.75f, kTol);
}

// A channel shorter than its animation holds its last key after it ends
// (glTF: values outside the key range are the first or last key's).
TEST(GltfAnimationInterpolation, ChannelClampsAfterItsLastKey) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 2, 3}, "VEC3", 2);
  // A second sampler and channel in the same animation, 4 s long.
  const int in = b.floats({0, 4}, "SCALAR", 2), out = b.floats({1, 1, 1, 1, 1, 1}, "VEC3", 2);
  b.doc["animations"][0]["samplers"].push_back({{"input", in}, {"output", out}});  // interpolation absent: LINEAR
  b.doc["animations"][0]["channels"].push_back({{"sampler", 1}, {"target", {{"node", 1}, {"path", "scale"}}}});
  const Scene s = b.load();
  EXPECT_DOUBLE_EQ(s.animation.animations[0].duration, 4.0);
  const glm::vec3 late = translationAt(s, 2, 3.0);
  EXPECT_NEAR(late.x, 1.0f, kTol);
  EXPECT_NEAR(late.y, 2.0f, kTol);
  EXPECT_NEAR(late.z, 3.0f, kTol);
}

// CUBICSPLINE rotation from identity to 90 degrees about Z (all tangents 0):
// halfway, h00 = h01 = 1/2, the sum (0,0,0.354,0.854) normalized: 45 degrees.
// Fails without the normalization (the matrix would shrink by |q|^2 = 0.854).
TEST(GltfAnimationInterpolation, CubicSplineRotationIsNormalized) {
  const float s45 = std::sqrt(0.5f);
  GltfBuilder b = rig();
  b.animate(2, "rotation", "CUBICSPLINE", {0, 1},
            {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, s45, s45, 0, 0, 0, 0}, "VEC4", 6);
  const Scene s = b.load();
  const glm::mat4 local = evaluatePose(s.animation, 0.5).local[2];
  const glm::mat4 want = glm::translate(glm::mat4(1), glm::vec3(0, 0, 10)) *
                         glm::rotate(glm::mat4(1), glm::radians(45.0f), glm::vec3(0, 0, 1));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(local[c][r], want[c][r], kTol) << c << "," << r;
}

// The rig skinned: joint 1 (node 2) moved by (0,5,0) drags vertex 1 along
// and vertex 2 half as far; the morph target's default weight 0.25 lifts
// every vertex by 0.25 in z first. Animated weights override the default.
TEST(GltfAnimationInterpolation, RigSkinAndMorphTogether) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "LINEAR", {0, 1}, {0, 0, 10, 0, 10, 10}, "VEC3", 2);  // t = 0.5: (0,5,10)
  b.animate(0, "weights", "LINEAR", {0, 1}, {0, 1}, "SCALAR", 2);                   // t = 0.5: 0.5
  const Scene s = b.load();
  {
    const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.5, 0), 0);
    EXPECT_NEAR(d.positions[0].y, 0.0f, kTol);
    EXPECT_NEAR(d.positions[1].y, 5.0f, kTol);
    EXPECT_NEAR(d.positions[2].y, 1.0f + 2.5f, kTol);
    EXPECT_NEAR(d.positions[1].z, 0.25f, kTol);  // default weight: animation 1 not played
  }
  {
    const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.5, 1), 0);
    EXPECT_NEAR(d.positions[1].y, 0.0f, kTol);  // rest skeleton
    EXPECT_NEAR(d.positions[1].z, 0.5f, kTol);  // animated weight
  }
  {
    const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.5, kAllAnimations), 0);
    EXPECT_NEAR(d.positions[2].y, 3.5f, kTol);
    EXPECT_NEAR(d.positions[2].z, 0.5f, kTol);
  }
}

// JOINTS_1/WEIGHTS_1: 8 influences. Vertex 0 gives joint 0 (identity) a
// normalized UNSIGNED_BYTE weight 51/255 = 0.2 in set 0 (UNSIGNED_SHORT
// joints) and joint 1, moved by (0,0,5), FLOAT weight 0.8 in set 1
// (UNSIGNED_BYTE joints): z = 0.25 (morph) + 0.8 * 5 = 4.25.
// Fails when set 1 is ignored (z = 0.2 * 0.25 = 0.05).
TEST(GltfAnimationInterpolation, SecondInfluenceSet) {
  GltfBuilder b = rig();
  const int j0 = b.accessor(std::vector<uint16_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, animtest::kU16, "VEC4", 3);
  const int w0 =
      b.accessor(std::vector<uint8_t>{51, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0}, animtest::kU8, "VEC4", 3, true);
  const int j1 = b.accessor(std::vector<uint8_t>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, animtest::kU8, "VEC4", 3);
  const int w1 = b.floats({0.8f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4", 3);
  auto& attrs = b.doc["meshes"][0]["primitives"][0]["attributes"];
  attrs["JOINTS_0"] = j0;
  attrs["WEIGHTS_0"] = w0;
  attrs["JOINTS_1"] = j1;
  attrs["WEIGHTS_1"] = w1;
  b.doc["nodes"][2]["translation"] = {0, 0, 15};  // joint matrix 1: T(0,0,5)
  const Scene s = b.load();
  const MeshData& m = s.meshes[0];
  ASSERT_EQ(m.influences.size(), 2u);
  EXPECT_NEAR(m.influences[0].weights[0].x, 0.2f, kTol);
  const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.0, kRestPose), 0);
  EXPECT_NEAR(d.positions[0].z, 4.25f, kTol);
}

// Morph NORMAL and TANGENT deltas (the tangents of a normal-mapped
// material, from the file): normal (0,0,1) + 1 * (1,0,0) -> (1,0,1)/sqrt 2;
// tangent (1,0,0,-1) + 1 * (0,1,0) -> (1,1,0)/sqrt 2, handedness kept.
TEST(GltfAnimationInterpolation, MorphNormalsAndTangents) {
  GltfBuilder b = rig();
  const int n = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int t = b.floats({1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1}, "VEC4", 3);
  const int dn = b.floats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3", 3);
  const int dt = b.floats({0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3);
  auto& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["NORMAL"] = n;
  prim["attributes"]["TANGENT"] = t;
  prim["attributes"]["TEXCOORD_0"] = b.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
  prim["targets"][0]["NORMAL"] = dn;
  prim["targets"][0]["TANGENT"] = dt;
  prim["material"] = 0;
  b.doc["meshes"][0]["weights"] = {1.0};
  b.doc["materials"] = nlohmann::json::parse(R"([{"normalTexture": {"index": 0}}])");
  b.doc["textures"] = nlohmann::json::parse(R"([{"source": 0}])");
  b.doc["images"] = {{{"uri", "data:image/png;base64," + scenetest::base64(scenetest::tinyPng())}}};
  const Scene s = b.load();
  const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.0, kRestPose), 0);
  const float h = std::sqrt(0.5f);
  ASSERT_EQ(d.tangents.size(), 3u);
  for (int v = 0; v < 3; ++v) {
    EXPECT_NEAR(d.normals[size_t(v)].x, h, kTol);
    EXPECT_NEAR(d.normals[size_t(v)].z, h, kTol);
    EXPECT_NEAR(d.tangents[size_t(v)].x, h, kTol);
    EXPECT_NEAR(d.tangents[size_t(v)].y, h, kTol);
    EXPECT_EQ(d.tangents[size_t(v)].w, -1.0f);
  }
}

// A scene file's model transform stands above the file's roots: the rig
// placed at x = 100 deforms to the same vertices moved by 100.
TEST(GltfAnimationInterpolation, AppendedSceneKeepsItsHierarchy) {
  GltfBuilder b = rig();
  b.animate(2, "translation", "LINEAR", {0, 1}, {0, 0, 10, 0, 10, 10}, "VEC3", 2);
  const Scene alone = b.load();
  Scene both = b.load();
  appendScene(both, b.load(), glm::translate(glm::mat4(1), glm::vec3(100, 0, 0)));
  ASSERT_EQ(both.animation.nodes.size(), 6u);
  ASSERT_EQ(both.animation.skins.size(), 2u);
  EXPECT_EQ(both.animation.skins[1].joints, (std::vector<int>{4, 5}));
  ASSERT_EQ(both.primitives.size(), 2u);
  EXPECT_EQ(both.primitives[1].node, 3);
  both.validate();
  const DeformedVertices a = deformPrimitive(alone, evaluatePose(alone.animation, 0.5), 0);
  const Pose pose = evaluatePose(both.animation, 0.5, kAllAnimations);
  const DeformedVertices first = deformPrimitive(both, pose, 0), second = deformPrimitive(both, pose, 1);
  for (size_t v = 0; v < 3; ++v) {
    EXPECT_NEAR(first.positions[v].x, a.positions[v].x, kTol);
    EXPECT_NEAR(second.positions[v].x, a.positions[v].x + 100.0f, kTol);
    EXPECT_NEAR(second.positions[v].y, a.positions[v].y, kTol);
  }
}

TEST(GltfAnimationInterpolation, LoopTime) {
  EXPECT_DOUBLE_EQ(loopTime(2.5, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(loopTime(-0.25, 2.0), 1.75);
  EXPECT_DOUBLE_EQ(loopTime(4.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(loopTime(3.0, 0.0), 0.0);
}
