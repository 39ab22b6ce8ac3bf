// Every refusal of broken animation, skin and morph data names the file, the
// JSON pointer of the value at fault and what is wrong (like the rest of the
// glTF loader); one case per diagnostic, on the rig of gltf_animation_rig.h.

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gltf_animation_rig.h"
#include "rgraph/animation.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"
#include "scene_test_util.h"

using namespace rgraph;
using animtest::GltfBuilder;
using nlohmann::json;

namespace {

struct Case {
  const char* name;
  std::function<void(GltfBuilder&)> breakIt;
  std::string pointer;  // the JSON pointer the message must name
  std::string message;  // and words it must say
};

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A translation animation of node 2 (the rig's second joint) to break.
void translation(GltfBuilder& b) { b.animate(2, "translation", "LINEAR", {0, 1}, {0, 0, 10, 0, 5, 10}, "VEC3", 2); }

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      // ---- samplers
      {"InputNotIncreasing",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {0, 1, 1}, std::vector<float>(9, 0.0f), "VEC3", 3);
       },
       "/animations/0/samplers/0/input",
       "key times must increase strictly: key 2 (1.000000 s) does not come after key 1"},
      {"InputNegative",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {-1, 1}, std::vector<float>(6, 0.0f), "VEC3", 2);
       },
       "/animations/0/samplers/0/input", "key 0 is at a negative time"},
      {"InputNotFinite",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {kNaN, 1}, std::vector<float>(6, 0.0f), "VEC3", 2);
       },
       "/animations/0/samplers/0/input", "element 0 is not finite"},
      {"InputEmpty", [](GltfBuilder& b) { b.animate(2, "translation", "LINEAR", {}, {}, "VEC3", 0); },
       "/animations/0/samplers/0/input", "has no keyframes"},
      {"OutputNotFinite",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {0, 1}, {0, 0, 0, 0, kNaN, 0}, "VEC3", 2);
       },
       "/animations/0/samplers/0/output", "element 1 is not finite"},
      {"OutputCountLinear",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {0, 1}, std::vector<float>(9, 0.0f), "VEC3", 3);
       },
       "/animations/0/samplers/0/output", "has 3 elements for 2 keys; LINEAR translation needs 2"},
      {"OutputCountCubic",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "CUBICSPLINE", {0, 1}, std::vector<float>(6, 0.0f), "VEC3", 2);
       },
       "/animations/0/samplers/0/output", "has 2 elements for 2 keys; CUBICSPLINE translation needs 6"},
      {"OutputCountWeights",
       [](GltfBuilder& b) {
         b.animate(0, "weights", "LINEAR", {0, 1}, {0, 0, 0}, "SCALAR", 3);
       },
       "/animations/0/samplers/0/output", "has 3 elements for 2 keys; LINEAR weights needs 2"},
      {"OutputType",
       [](GltfBuilder& b) {
         b.animate(2, "rotation", "LINEAR", {0, 1}, std::vector<float>(6, 0.0f), "VEC3", 2);
       },
       "/animations/0/samplers/0/output", "a rotation channel needs VEC4 output"},
      {"CubicOneKey",
       [](GltfBuilder& b) { b.animate(2, "translation", "CUBICSPLINE", {0}, std::vector<float>(9, 0.0f), "VEC3", 3); },
       "/animations/0/samplers/0/input", "CUBICSPLINE needs at least 2 keyframes"},
      {"UnknownInterpolation",
       [](GltfBuilder& b) {
         translation(b);
         b.doc["animations"][0]["samplers"][0]["interpolation"] = "BEZIER";
       },
       "/animations/0/samplers/0/interpolation", "unknown interpolation 'BEZIER' (STEP, LINEAR or CUBICSPLINE)"},
      {"ZeroQuaternion",
       [](GltfBuilder& b) {
         b.animate(2, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}, "VEC4", 2);
       },
       "/animations/0/samplers/0/output", "rotation key 1 is a zero quaternion"},
      {"AnimationBudget",
       [](GltfBuilder& b) {
         translation(b);
         // 2^24 matrices of zeros (no buffer view): 2^28 values, never read.
         b.doc["accessors"].push_back({{"componentType", animtest::kFloat}, {"count", 1 << 24}, {"type", "MAT4"}});
         b.doc["animations"][0]["samplers"][0]["output"] = b.doc["accessors"].size() - 1;
       },
       "/animations/0/samplers/0", "the animations hold more than 134217728 key times and values in all"},
      // ---- channels
      {"ChannelNode",
       [](GltfBuilder& b) {
         translation(b);
         b.doc["animations"][0]["channels"][0]["target"]["node"] = 7;
       },
       "/animations/0/channels/0/target/node", "node 7 does not exist (3 nodes)"},
      {"ChannelSampler",
       [](GltfBuilder& b) {
         translation(b);
         b.doc["animations"][0]["channels"][0]["sampler"] = 3;
       },
       "/animations/0/channels/0/sampler", "sampler 3 does not exist (1 samplers)"},
      {"ChannelMatrixNode",
       [](GltfBuilder& b) {
         translation(b);
         b.doc["nodes"][2].erase("translation");
         b.doc["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 10, 1};
       },
       "/animations/0/channels/0/target/node", "node 2 is given by a matrix"},
      {"WeightsWithoutTargets",
       [](GltfBuilder& b) {
         b.animate(2, "weights", "LINEAR", {0, 1}, {0, 1}, "SCALAR", 2);
       },
       "/animations/0/channels/0/target/node", "animates the morph weights of node 2, whose mesh has no morph targets"},
      {"SamplerSharedWithAnotherPath",
       [](GltfBuilder& b) {
         b.animate(2, "translation", "LINEAR", {0, 1}, std::vector<float>(6, 0.0f), "VEC3", 2);
         b.doc["animations"][0]["channels"].push_back({{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}});
       },
       "/animations/0/samplers/0/output", "a weights channel needs SCALAR output"},
      // ---- skins
      {"SkinJointNode", [](GltfBuilder& b) { b.doc["skins"][0]["joints"][1] = 9; }, "/skins/0/joints/1",
       "node 9 does not exist (3 nodes)"},
      {"SkinNoJoints", [](GltfBuilder& b) { b.doc["skins"][0]["joints"] = json::array(); }, "/skins/0/joints",
       "a skin needs at least one joint"},
      {"SkinSkeleton", [](GltfBuilder& b) { b.doc["skins"][0]["skeleton"] = 5; }, "/skins/0/skeleton",
       "node 5 does not exist (3 nodes)"},
      {"InverseBindCount",
       [](GltfBuilder& b) {
         b.doc["skins"][0]["inverseBindMatrices"] = b.floats(std::vector<float>(16, 1.0f), "MAT4", 1);
       },
       "/skins/0/inverseBindMatrices", "has 1 matrices for 2 joints"},
      {"InverseBindNotFinite",
       [](GltfBuilder& b) {
         std::vector<float> m(32, 0.0f);
         m[20] = kNaN;
         b.doc["skins"][0]["inverseBindMatrices"] = b.floats(m, "MAT4", 2);
       },
       "/skins/0/inverseBindMatrices", "element 1 is not finite"},
      {"NodeSkin", [](GltfBuilder& b) { b.doc["nodes"][0]["skin"] = 4; }, "/nodes/0/skin",
       "skin 4 does not exist (1 skins)"},
      {"JointOutsideSkin",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] =
             b.accessor(std::vector<uint8_t>{0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0}, animtest::kU8, "VEC4", 3);
       },
       "/meshes/0/primitives/0/attributes/JOINTS_0",
       "joint index 2 (vertex 1) is outside skin 0 of node 0, which has 2 joints"},
      {"JointsWithoutWeights",
       [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0"); },
       "/meshes/0/primitives/0/attributes/JOINTS_0", "has no matching WEIGHTS_0"},
      {"WeightsNotNormalized",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             b.accessor(std::vector<uint8_t>(12, 1), animtest::kU8, "VEC4", 3);
       },
       "/meshes/0/primitives/0/attributes/WEIGHTS_0", "integer weights must be normalized"},
      {"WeightsNotFinite",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             b.floats({1, 0, 0, 0, 1, 0, 0, 0, kNaN, 0, 0, 0}, "VEC4", 3);
       },
       "/meshes/0/primitives/0/attributes/WEIGHTS_0", "element 2 is not finite"},
      {"WeightsCount",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] =
             b.floats(std::vector<float>(8, 0.5f), "VEC4", 2);
       },
       "/meshes/0/primitives/0/attributes/WEIGHTS_0", "count 2 differs from the POSITION count 3"},
      // ---- morph targets and weights
      {"TargetCount",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] =
             b.floats(std::vector<float>(6, 0.0f), "VEC3", 2);
       },
       "/meshes/0/primitives/0/targets/0/POSITION", "count 2 differs from the POSITION count 3"},
      {"TargetNotFinite",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] =
             b.floats({0, 0, 0, 0, 0, 0, 0, 0, kNaN}, "VEC3", 3);
       },
       "/meshes/0/primitives/0/targets/0/POSITION", "element 2 is not finite"},
      {"TargetsDifferBetweenPrimitives",
       [](GltfBuilder& b) {
         json p = b.doc["meshes"][0]["primitives"][0];
         p.erase("targets");
         b.doc["meshes"][0]["primitives"].push_back(p);
       },
       "/meshes/0/primitives/1/targets", "has 0 morph targets, primitive 0 has 1"},
      {"MeshWeightsCount",
       [](GltfBuilder& b) {
         b.doc["meshes"][0]["weights"] = {0.5, 0.5};
       },
       "/meshes/0/weights", "has 2 weights for 1 morph targets"},
      {"NodeWeightsCount",
       [](GltfBuilder& b) {
         b.doc["nodes"][0]["weights"] = {0.5, 0.5, 0.5};
       },
       "/nodes/0/weights", "has 3 weights for 1 morph targets"},
      // ---- nodes outside the default scene (the traversal never sees them)
      {"NodeOutsideSceneTranslation",
       [](GltfBuilder& b) {
         b.doc["nodes"].push_back({{"translation", {0, 1}}});
       },
       "/nodes/3/translation", "must have 3 numbers"},
      {"CycleOutsideScene",
       [](GltfBuilder& b) {
         b.doc["nodes"].push_back({{"children", {4}}});
         b.doc["nodes"].push_back({{"children", {3}}});
       },
       "/nodes/3", "is its own ancestor (cycle in the node hierarchy)"},
  };
  return all;
}

}  // namespace

TEST(GltfAnimationErrors, EachRefusalNamesThePointer) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    GltfBuilder b = animtest::rig();
    c.breakIt(b);
    try {
      b.load();
      ADD_FAILURE() << c.name << ": loaded without an error";
    } catch (const RuntimeError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind("anim.gltf:", 0), 0u) << msg;
      EXPECT_NE(msg.find(": " + c.pointer + ": "), std::string::npos) << msg;
      EXPECT_NE(msg.find(c.message), std::string::npos) << msg;
    }
  }
}

// The unbroken rig loads (so that each case above fails for its own reason).
TEST(GltfAnimationErrors, TheRigLoads) {
  GltfBuilder b = animtest::rig();
  translation(b);
  const Scene s = b.load();
  EXPECT_EQ(s.animation.nodes.size(), 3u);
  EXPECT_EQ(s.animation.skins.size(), 1u);
  EXPECT_EQ(s.animation.animations.size(), 1u);
  ASSERT_EQ(s.primitives.size(), 1u);
  EXPECT_EQ(s.primitives[0].node, 0);
}

// A channel path glTF does not define (KHR_animation_pointer's "pointer",
// say) is skipped with a warning at its pointer; the rest plays.
TEST(GltfAnimationErrors, UnknownPathIsIgnoredWithAWarning) {
  GltfBuilder b = animtest::rig();
  translation(b);
  b.doc["animations"][0]["channels"].push_back({{"sampler", 0}, {"target", {{"node", 2}, {"path", "pointer"}}}});
  const Scene s = b.load();
  EXPECT_EQ(s.animation.animations[0].channels.size(), 1u);
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned = warned ||
             (w.find("/animations/0/channels/1/target/path: animation path 'pointer' is not supported; the channel is "
                     "ignored") != std::string::npos);
  EXPECT_TRUE(warned);
}

// Evaluation's own errors: an animation index the scene lacks, a primitive
// it lacks, a pose made for another scene.
TEST(GltfAnimationErrors, EvaluationErrors) {
  GltfBuilder b = animtest::rig();
  translation(b);
  const Scene s = b.load();
  EXPECT_THROW(evaluatePose(s.animation, 0.0, 1), RuntimeError);
  EXPECT_THROW(evaluatePose(s.animation, 0.0, -3), RuntimeError);
  try {
    deformPrimitive(s, evaluatePose(s.animation, 0.0), 4);
    ADD_FAILURE() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(), "deformPrimitive: primitive 4 does not exist (1 primitives)");
  }
  try {
    deformPrimitive(s, Pose{}, 0);
    ADD_FAILURE() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(), "deformPrimitive: the pose was not evaluated for this scene's animation");
  }
}
