// glTF animation, skins and morph targets evaluated on the CPU
// (rgraph/animation.h) against values derived by hand from the sample files'
// keyframes (/work/shared/assets/gltf; the key values quoted in comments
// were read from their .bin files). Each expectation names the glTF rule it
// checks; turning that rule off in the library makes it fail (see the
// comments "fails without").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using scenetest::asset;

namespace {

// Positions: 1e-5 scene units for the unit-sized samples (float rounding of
// a few matrix products), 2e-3 for RecursiveSkeletons (90 units tall, 30
// chained joints: relative 2e-5).
constexpr float kTol = 1e-5f;

void expectNear(const glm::vec3& got, const glm::vec3& want, float tol, const std::string& what) {
  EXPECT_NEAR(got.x, want.x, tol) << what;
  EXPECT_NEAR(got.y, want.y, tol) << what;
  EXPECT_NEAR(got.z, want.z, tol) << what;
}

void expectMatNear(const glm::mat4& got, const glm::mat4& want, float tol, const std::string& what) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(got[c][r], want[c][r], tol) << what << " [" << c << "][" << r << "]";
}

size_t primitiveOfNode(const Scene& s, int node) {
  for (size_t i = 0; i < s.primitives.size(); ++i)
    if (s.primitives[i].node == node) return i;
  ADD_FAILURE() << "no primitive drawn by node " << node;
  return 0;
}

// The .gltf's JSON, edited by `edit`, loaded from memory with the sample's
// own folder for its buffers.
Scene loadEdited(const std::string& rel, const std::function<void(nlohmann::json&)>& edit) {
  std::ifstream f(asset(rel));
  nlohmann::json doc = nlohmann::json::parse(f);
  edit(doc);
  const std::string text = doc.dump();
  const std::string dir = asset(rel.substr(0, rel.find('/')));
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(text.data()), text.size(), rel, dir);
}

}  // namespace

// AnimatedCube: one LINEAR rotation channel, keys at 0, 1, 2 s:
//   (0,0,0,1), (0,1,0,-4.371139e-8), (0,-8.742278e-8,0,-1)   (x,y,z,w).
// Consecutive keys have a dot product of -4.4e-8: glTF's slerp negates the
// second key (shortest path), so at t = 0.5 the cube has turned -90 degrees
// about +Y (quaternion (0,-sqrt(1/2),0,sqrt(1/2))) and at 1.5 s +90 degrees.
// Fails without the shortest path (+90 and -90 instead).
TEST(GltfAnimationSamples, AnimatedCubeSlerpsAlongTheShortestArc) {
  const Scene s = loadGltf(asset("AnimatedCube/AnimatedCube.gltf"));
  ASSERT_EQ(s.animation.animations.size(), 1u);
  EXPECT_DOUBLE_EQ(s.animation.animations[0].duration, 2.0);
  ASSERT_EQ(s.primitives.size(), 1u);
  ASSERT_EQ(s.primitives[0].node, 0);
  // R_y(-90): x -> +z, z -> -x.
  const glm::mat4 minus90(glm::vec4(0, 0, 1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(-1, 0, 0, 0), glm::vec4(0, 0, 0, 1));
  const glm::mat4 plus90(glm::vec4(0, 0, -1, 0), glm::vec4(0, 1, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(0, 0, 0, 1));
  expectMatNear(evaluatePose(s.animation, 0.5).world[0], minus90, kTol, "t = 0.5");
  expectMatNear(evaluatePose(s.animation, 1.5).world[0], plus90, kTol, "t = 1.5");
  // Looping (the caller's clock modulo the 2 s duration), negative clocks too.
  expectMatNear(evaluatePose(s.animation, 2.5).world[0], minus90, kTol, "t = 2.5");
  expectMatNear(evaluatePose(s.animation, -1.5).world[0], minus90, kTol, "t = -1.5");
  expectMatNear(evaluatePose(s.animation, 1000.5).world[0], minus90, kTol, "t = 1000.5");
  // The rest pose is the node's own rotation (0,-1,0,0): 180 degrees about Y.
  const glm::mat4 half(glm::vec4(-1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, -1, 0), glm::vec4(0, 0, 0, 1));
  expectMatNear(evaluatePose(s.animation, 0.5, kRestPose).world[0], half, kTol, "rest");
  expectMatNear(s.primitives[0].transform, half, kTol, "Primitive::transform (drawn at rest)");

  // Deformed vertices: every position (x, y, z) at t = 0.5 is (-z, y, x),
  // every normal likewise.
  const DeformedVertices d = deformPrimitive(s, evaluatePose(s.animation, 0.5), 0);
  const MeshData& m = s.meshes[0];
  ASSERT_EQ(d.positions.size(), m.vertexCount());
  for (size_t v = 0; v < m.vertexCount(); ++v) {
    const glm::vec3 p = m.positions[v], n = m.normals[v];
    expectNear(d.positions[v], glm::vec3(-p.z, p.y, p.x), kTol, "position " + std::to_string(v));
    expectNear(d.normals[v], glm::vec3(-n.z, n.y, n.x), kTol, "normal " + std::to_string(v));
  }
}

// SimpleSkin: joints [node 1, node 2]; node 2 at (0,1,0) turns about Z by the
// LINEAR channel (keys every 0.5 s: (0,0,0,1), (0,0,0.383,0.924),
// (0,0,0.707,0.707), ...); inverse bind matrices identity and T(0,-1,0).
// Joint matrix 1 = world(node 2) * T(0,-1,0) turns the upper half about (0,1,0).
TEST(GltfAnimationSamples, SimpleSkinJointMatricesAndSkinnedVertices) {
  const Scene s = loadGltf(asset("SimpleSkin/SimpleSkin.gltf"));
  ASSERT_EQ(s.animation.skins.size(), 1u);
  ASSERT_EQ(s.animation.skins[0].joints, (std::vector<int>{1, 2}));
  const size_t prim = primitiveOfNode(s, 0);
  const MeshData& m = s.meshes[s.primitives[prim].mesh];
  ASSERT_TRUE(m.skinned());

  // A rotation of `deg` about Z through (0,1,0).
  auto aboutJoint = [](float deg) {
    return glm::translate(glm::mat4(1), glm::vec3(0, 1, 0)) *
           glm::rotate(glm::mat4(1), glm::radians(deg), glm::vec3(0, 0, 1)) *
           glm::translate(glm::mat4(1), glm::vec3(0, -1, 0));
  };
  // t = 1 s: key 2 exactly, (0,0,0.707,0.707) normalized: 90 degrees.
  {
    const Pose pose = evaluatePose(s.animation, 1.0);
    const std::span<const glm::mat4> joints = pose.skinJoints(s.animation, 0);
    ASSERT_EQ(joints.size(), 2u);
    expectMatNear(joints[0], glm::mat4(1.0f), kTol, "joint 0");
    expectMatNear(joints[1], aboutJoint(90.0f), kTol, "joint 1");
    const DeformedVertices d = deformPrimitive(s, pose, prim);
    // The file's vertices (unwelded by the loader's flat normals) and
    // weights: y 0 -> (1, 0), 0.5 -> (0.75, 0.25), 1 -> (0.5, 0.5),
    // 1.5 -> (0.25, 0.75), 2 -> (0, 1). At 90 degrees joint 1 takes
    // (x, y) to (1 - y, x + 1).
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec3 p = m.positions[v];
      const float w1 = p.y / 2.0f;  // the file's weights: linear in height
      const glm::vec3 turned(-(p.y - 1.0f), p.x + 1.0f, 0.0f);
      expectNear(d.positions[v], (1.0f - w1) * p + w1 * turned, kTol, "t = 1, vertex " + std::to_string(v));
    }
  }
  // t = 0.125 s: a quarter of the way from key 0 to key 1: slerp turns by a
  // quarter of key 1's angle 2 atan2(0.383, 0.924) = 45.04 degrees, 11.26
  // degrees (fails with a normalized lerp instead: 11.15 degrees, 2e-3 off at
  // the top vertices).
  {
    const float deg = 0.25f * glm::degrees(2.0f * std::atan2(0.383f, 0.924f));
    const Pose pose = evaluatePose(s.animation, 0.125);
    expectMatNear(pose.skinJoints(s.animation, 0)[1], aboutJoint(deg), kTol, "joint 1 at t = 0.125");
    const DeformedVertices d = deformPrimitive(s, pose, prim);
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec3 p = m.positions[v];
      const float w1 = p.y / 2.0f;
      const glm::vec3 turned(aboutJoint(deg) * glm::vec4(p, 1.0f));
      expectNear(d.positions[v], (1.0f - w1) * p + w1 * turned, kTol, "t = 0.125, vertex " + std::to_string(v));
    }
  }
}

// glTF: "the transform of the node that references the skin is ignored":
// SimpleSkin with its mesh node moved 5 units along X deforms the same.
// Fails when the skinned node's world matrix is applied.
TEST(GltfAnimationSamples, SkinnedNodeTransformIsIgnored) {
  const Scene plain = loadGltf(asset("SimpleSkin/SimpleSkin.gltf"));
  const Scene moved = loadEdited("SimpleSkin/SimpleSkin.gltf", [](nlohmann::json& d) {
    d["nodes"][0]["translation"] = {5.0, 0.0, 0.0};
  });
  const DeformedVertices a = deformPrimitive(plain, evaluatePose(plain.animation, 0.75), 0);
  const DeformedVertices b = deformPrimitive(moved, evaluatePose(moved.animation, 0.75), 0);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t v = 0; v < a.positions.size(); ++v)
    expectNear(b.positions[v], a.positions[v], kTol, "vertex " + std::to_string(v));
}

// RecursiveSkeletons: skin 1's joints (nodes 11-20) hang below skin 0's last
// joint (node 9), skin 2's (22-31) below skin 1's last (node 20). Every one
// of those 30 joints turns about X by the same LINEAR channel (keys 0, 1, 2 s:
// identity, (0.0998334,0,0,0.9950042), identity); node 0 stands at
// (25,0,25), nodes 1-9 at (0,10,0) below their parent, a skin's first joint
// at (3,0,3) scaled 0.3. A vertex bound to joint 9 at height 90 sits at
// (x, 0, z) in that joint's frame (inverse bind matrix T(0,-90,0)).
TEST(GltfAnimationSamples, RecursiveSkeletonsNestedJointsCarryTheirParents) {
  const Scene s = loadGltf(asset("RecursiveSkeletons/RecursiveSkeletons.glb"));
  ASSERT_EQ(s.animation.skins.size(), 84u);
  for (const double t : {0.5, 1.0}) {
    // At 1 s the key's angle; at 0.5 s half of it (slerp at u = 0.5).
    const float angle = float(t) * 2.0f * std::atan2(0.0998334f, 0.9950042f);
    const glm::mat4 R = glm::rotate(glm::mat4(1), angle, glm::vec3(1, 0, 0));
    const glm::mat4 up = glm::translate(glm::mat4(1), glm::vec3(0, 10, 0)) * R;
    glm::mat4 chain(1.0f);  // joints 1-9 of a skin, below its first
    for (int i = 0; i < 9; ++i) chain = chain * up;
    const glm::mat4 first0 = glm::translate(glm::mat4(1), glm::vec3(25, 0, 25)) * R;
    const glm::mat4 firstN =
        glm::translate(glm::mat4(1), glm::vec3(3, 0, 3)) * R * glm::scale(glm::mat4(1), glm::vec3(0.3f));
    const glm::mat4 joint9[3] = {first0 * chain, first0 * chain * firstN * chain,
                                 first0 * chain * firstN * chain * firstN * chain};
    const Pose pose = evaluatePose(s.animation, t);
    const int meshNode[3] = {10, 21, 32};  // the nodes drawing skins 0, 1, 2
    for (int level = 0; level < 3; ++level) {
      const size_t prim = primitiveOfNode(s, meshNode[level]);
      const MeshData& m = s.meshes[s.primitives[prim].mesh];
      const DeformedVertices d = deformPrimitive(s, pose, prim);
      int checked = 0;
      for (size_t v = 0; v < m.vertexCount(); ++v) {
        if (m.positions[v].y != 90.0f) continue;  // the top ring: joint 9 alone
        const glm::vec3 local(m.positions[v].x, 0.0f, m.positions[v].z);
        expectNear(d.positions[v], glm::vec3(joint9[level] * glm::vec4(local, 1.0f)), 2e-3f,
                   "t = " + std::to_string(t) + ", skin " + std::to_string(level) + ", vertex " + std::to_string(v));
        ++checked;
      }
      EXPECT_GE(checked, 4) << "level " << level;
    }
  }
}

// SimpleMorph: two POSITION targets, mesh weights (0.5, 0.5), a LINEAR
// weights channel with keys at 0..4 s: (0,0), (0,1), (1,1), (1,0), (0,0).
// Vertex 2 is (0.5,0.5,0); target 0 moves it by (-1,1,0), target 1 by (1,1,0).
TEST(GltfAnimationSamples, SimpleMorphWeightsAnimateAndDeform) {
  const Scene s = loadGltf(asset("SimpleMorph/SimpleMorph.gltf"));
  const size_t prim = 0;
  ASSERT_EQ(s.meshes[s.primitives[prim].mesh].morphTargets.size(), 2u);
  auto vertex2 = [&](double t, int animation) {
    const Pose pose = evaluatePose(s.animation, t, animation);
    return std::make_pair(
        std::vector<float>(pose.nodeWeights(s.animation, 0).begin(), pose.nodeWeights(s.animation, 0).end()),
        deformPrimitive(s, pose, prim).positions);
  };
  struct Case {
    double t;
    int animation;
    std::vector<float> weights;
    glm::vec3 v2;
  };
  const Case cases[] = {
      {0.0, kRestPose, {0.5f, 0.5f}, {0.5f, 1.5f, 0.0f}},  // the mesh's default weights
      {0.0, 0, {0.0f, 0.0f}, {0.5f, 0.5f, 0.0f}},
      {1.5, 0, {0.5f, 1.0f}, {1.0f, 2.0f, 0.0f}},      // halfway from (0,1) to (1,1)
      {2.25, 0, {1.0f, 0.75f}, {0.25f, 2.25f, 0.0f}},  // a quarter from (1,1) to (1,0)
      {4.5, 0, {0.0f, 0.5f}, {1.0f, 1.0f, 0.0f}},      // looped: 0.5 s
  };
  for (const Case& c : cases) {
    const auto [w, positions] = vertex2(c.t, c.animation);
    const std::string what = "t = " + std::to_string(c.t) + " animation " + std::to_string(c.animation);
    ASSERT_EQ(w.size(), 2u) << what;
    EXPECT_NEAR(w[0], c.weights[0], kTol) << what;
    EXPECT_NEAR(w[1], c.weights[1], kTol) << what;
    expectNear(positions[2], c.v2, kTol, what);
    expectNear(positions[0], glm::vec3(0, 0, 0), kTol, what);  // no deltas
    expectNear(positions[1], glm::vec3(1, 0, 0), kTol, what);
  }
}

// MorphPrimitivesTest: no animation; the mesh's default weight 0.5 on one
// target per primitive, each moving some vertices by (0, 0.2, 0) (primitive
// 0: vertices 13-20, primitive 1: 5-8): they rise by 0.1, the rest stay.
// Fails when default weights are not applied.
TEST(GltfAnimationSamples, MorphPrimitivesTestDefaultWeights) {
  const Scene s = loadGltf(asset("MorphPrimitivesTest/MorphPrimitivesTest.glb"));
  ASSERT_TRUE(s.animation.animations.empty());
  ASSERT_EQ(s.primitives.size(), 2u);
  const std::set<size_t> moved[2] = {{13, 14, 15, 16, 17, 18, 19, 20}, {5, 6, 7, 8}};
  const Pose pose = evaluatePose(s.animation, 3.0, kRestPose);
  for (size_t p = 0; p < 2; ++p) {
    const MeshData& m = s.meshes[s.primitives[p].mesh];
    const DeformedVertices d = deformPrimitive(s, pose, p);
    const glm::mat4 world = s.primitives[p].transform;
    for (size_t v = 0; v < m.vertexCount(); ++v) {
      const glm::vec3 rest = m.positions[v] + glm::vec3(0.0f, moved[p].count(v) ? 0.1f : 0.0f, 0.0f);
      expectNear(d.positions[v], glm::vec3(world * glm::vec4(rest, 1.0f)), kTol,
                 "primitive " + std::to_string(p) + " vertex " + std::to_string(v));
    }
  }
  // Evaluating animation 0 of a file without animations is an error, said so.
  try {
    evaluatePose(s.animation, 0.0, 0);
    FAIL() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(), "animation 0 does not exist (the scene has 0 animations)");
  }
}

// Static files keep no node table: nothing to evaluate, nothing stored.
TEST(GltfAnimationSamples, StaticFilesKeepNoNodes) {
  const Scene s = loadGltf(asset("Box/Box.glb"));
  EXPECT_TRUE(s.animation.empty());
  for (const Primitive& p : s.primitives) EXPECT_EQ(p.node, -1);
  const DeformedVertices d = deformPrimitive(s, Pose{}, 0);
  const glm::vec3 p0 = s.meshes[s.primitives[0].mesh].positions[0];
  expectNear(d.positions[0], glm::vec3(s.primitives[0].transform * glm::vec4(p0, 1.0f)), kTol, "static vertex 0");
}
