// glTF animation drawn on the GPU (issue 30): the vertices scene.vert emits
// for SimpleSkin, RecursiveSkeletons, SimpleMorph, MorphPrimitivesTest and
// AnimatedCube posed by RenderScene::setTime, read back from a storage buffer
// scene.vert writes under CAPTURE_VERTICES (deform_capture.h), against the CPU reference deformer (deformPrimitive of
// evaluatePose at the same time). Tolerance: 1e-5 of the scene's size (the
// GPU sums the same joint matrices and deltas in float, in another order).
// Each case also checks that its feature moves the vertices by far more than
// that (>= 100x), so that drawing it undeformed fails the test. And: motion
// vectors of a skinned and a morphed mesh between two times against the
// CPU's displacement, bounds that hold the pose, setTime's refusals, and a
// static scene that uploads and binds nothing of this.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "deform_capture.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/renderer.h"
#include "support/posed_bounds_check.h"
#include "support/test_support.h"

using namespace rgraph;
using namespace deformtest;

namespace {

// A shared glTF sample's path, or a procedural scene's name ("walker") as is.
std::string spec(const std::string& file) { return file.find('.') == std::string::npos ? file : asset(file); }

struct GpuDeform : ::testing::Test {
  std::unique_ptr<ShaderLibrary> shaders;
  uint64_t errorsAtStart = 0;
  void SetUp() override {
    testsupport::sharedGlContext();
    shaders = std::make_unique<ShaderLibrary>();
    shaders->addSearchDirectory(std::string(RGRAPH_TEST_DATA_DIR) + "/animation_gpu/shaders");
    errorsAtStart = testsupport::sharedGlContext().debugErrorCount();
  }
  void TearDown() override {
    shaders.reset();
    EXPECT_EQ(testsupport::sharedGlContext().debugErrorCount(), errorsAtStart)
        << "GL debug errors, last: " << testsupport::sharedGlContext().lastDebugError();
  }

  // Poses `file` at `seconds` through RenderScene::setTime and compares the
  // GPU's vertices with the CPU's; returns {GPU error, how far the feature
  // moved the vertices from the undeformed draw} relative to the scene size.
  std::pair<float, float> compare(const std::string& file, double seconds) {
    std::shared_ptr<RenderScene> rs = RenderScene::load(spec(file));
    rs->setTime(seconds);
    GpuScene& gpu = rs->gpu();
    gpu.updateFrame({64, 64});
    const Captured got = DeformCapture(*shaders).capture(gpu);
    const Scene& s = rs->scene();
    const Pose pose = evaluatePose(s.animation, seconds, kAllAnimations);
    const float size = std::max(s.bounds().radius(), 1e-6f);
    float error = 0.0f, moved = 0.0f;
    size_t vertices = 0;
    for (size_t i = 0; i < s.primitives.size(); ++i) {
      const MeshData& m = s.meshes[size_t(s.primitives[i].mesh)];
      const DeformedVertices want = deformPrimitive(s, pose, i);
      // The undeformed draw: the loader's rest transform, no skin, no morph.
      const glm::mat4 rest = loadedTransforms[i];
      for (uint32_t v : drawnVertices(m)) {
        error = std::max(error, glm::distance(glm::vec3(got.world[i][v]), want.positions[v]));
        moved = std::max(moved, glm::distance(glm::vec3(rest * glm::vec4(m.positions[v], 1.0f)), want.positions[v]));
        ++vertices;
      }
    }
    error /= size;
    moved /= size;
    std::printf("[ measure  ] %s at %.3f s: %zu vertices, GPU vs CPU %.3g, the feature moved them %.3g (of the scene's radius %.3g)\n",
                file.c_str(), seconds, vertices, error, moved, size);
    return {error, moved};
  }
  std::vector<glm::mat4> loadedTransforms;
  std::pair<float, float> check(const std::string& file, double seconds) {
    const Scene loaded = loadSceneAny(spec(file));
    loadedTransforms.clear();
    for (const Primitive& p : loaded.primitives) loadedTransforms.push_back(p.transform);
    return compare(file, seconds);
  }
};

constexpr float kTolerance = 1e-5f;

}  // namespace

TEST_F(GpuDeform, SimpleSkinMatchesTheCpuSkin) {
  for (double t : {1.0, 2.25}) {
    const auto [error, moved] = check("SimpleSkin/SimpleSkin.gltf", t);
    EXPECT_LE(error, kTolerance) << "t = " << t;
    EXPECT_GE(moved, 100 * kTolerance) << "t = " << t;
  }
}

TEST_F(GpuDeform, RecursiveSkeletonsNestedSkinsMatchTheCpu) {
  const auto [error, moved] = check("RecursiveSkeletons/RecursiveSkeletons.glb", 0.75);
  EXPECT_LE(error, kTolerance);
  EXPECT_GE(moved, 100 * kTolerance);
}

// The bench's walk (procedural, 3 skins of 11 joints, 2 influences where
// limbs meet): the GPU's vertices are the CPU's mid-stride.
TEST_F(GpuDeform, WalkerSkinsMatchTheCpu) {
  const auto [error, moved] = check("walker", 0.35);
  EXPECT_LE(error, kTolerance);
  EXPECT_GE(moved, 100 * kTolerance);
}

TEST_F(GpuDeform, SimpleMorphAnimatedWeightsMatchTheCpu) {
  for (double t : {1.5, 2.25}) {
    const auto [error, moved] = check("SimpleMorph/SimpleMorph.gltf", t);
    EXPECT_LE(error, kTolerance) << "t = " << t;
    EXPECT_GE(moved, 100 * kTolerance) << "t = " << t;
  }
}

TEST_F(GpuDeform, MorphPrimitivesTestDefaultWeightsMatchTheCpu) {
  // No animation: the mesh's default weights (0.5) deform it at any time.
  const auto [error, moved] = check("MorphPrimitivesTest/MorphPrimitivesTest.glb", 3.0);
  EXPECT_LE(error, kTolerance);
  EXPECT_GE(moved, 100 * kTolerance);
}

TEST_F(GpuDeform, AnimatedCubeNodeRotationMatchesTheCpu) {
  const auto [error, moved] = check("AnimatedCube/AnimatedCube.gltf", 0.5);
  EXPECT_LE(error, kTolerance);
  EXPECT_GE(moved, 100 * kTolerance);
}

// Motion vectors: frame 1 at t0, frame 2 at t1 (the frame after): the
// velocity scene.vert gives each vertex (uv now - uv previous, from its clip
// positions) equals the CPU's displacement between the two poses projected
// with the same camera; within 1e-4 UV, and some vertex moves >= 0.01 UV
// (without the previous joints or weights it would be 0).
TEST_F(GpuDeform, MotionVectorsIncludeSkinningAndMorphing) {
  struct Case {
    const char* file;
    double t0, t1;
  };
  for (const Case& c : {Case{"SimpleSkin/SimpleSkin.gltf", 0.5, 0.75}, Case{"SimpleMorph/SimpleMorph.gltf", 1.0, 1.25}}) {
    std::shared_ptr<RenderScene> rs = RenderScene::load(asset(c.file));
    GpuScene& gpu = rs->gpu();
    const Camera cam = rs->scene().camera;
    const Extent vp{64, 64};
    rs->setTime(c.t0);
    FrameMotion m;
    m.frame = 1;
    const glm::mat4 viewProj = gpu.updateFrame(vp, cam, m);
    rs->setTime(c.t1);
    m.frame = 2;
    m.prevViewProj = viewProj;
    gpu.updateFrame(vp, cam, m);
    const Captured got = DeformCapture(*shaders).capture(gpu);
    const Scene& s = rs->scene();
    const Pose p0 = evaluatePose(s.animation, c.t0, kAllAnimations), p1 = evaluatePose(s.animation, c.t1, kAllAnimations);
    auto uv = [](const glm::vec4& clip) { return glm::vec2(clip) / clip.w * 0.5f; };
    float worst = 0.0f, largest = 0.0f;
    for (size_t i = 0; i < s.primitives.size(); ++i) {
      const DeformedVertices a = deformPrimitive(s, p0, i), b = deformPrimitive(s, p1, i);
      for (uint32_t v : drawnVertices(s.meshes[size_t(s.primitives[i].mesh)])) {
        const glm::vec2 gpuVelocity = uv(got.clipNow[i][v]) - uv(got.clipPrev[i][v]);
        const glm::vec2 cpuVelocity = uv(viewProj * glm::vec4(b.positions[v], 1.0f)) - uv(viewProj * glm::vec4(a.positions[v], 1.0f));
        worst = std::max(worst, glm::length(gpuVelocity - cpuVelocity));
        largest = std::max(largest, glm::length(cpuVelocity));
      }
    }
    std::printf("[ measure  ] %s %.2f -> %.2f s: largest velocity %.4f UV, GPU vs CPU %.3g UV\n", c.file, c.t0, c.t1,
                largest, worst);
    EXPECT_GE(largest, 0.01f) << c.file;
    EXPECT_LE(worst, 1e-4f) << c.file;
  }
}

// Bounds hold the pose (culling and shadow fitting read them): every CPU-deformed
// vertex of every primitive lies in its Primitive::bounds at several times.
TEST_F(GpuDeform, BoundsHoldEveryDeformedVertex) {
  for (const char* file : {"SimpleSkin/SimpleSkin.gltf", "RecursiveSkeletons/RecursiveSkeletons.glb",
                           "SimpleMorph/SimpleMorph.gltf", "AnimatedCube/AnimatedCube.gltf", "walker"}) {
    std::shared_ptr<RenderScene> rs = RenderScene::load(spec(file));
    for (double t : {0.0, 0.4, 1.1, 2.6, 3.3}) {
      rs->setTime(t);
      const Scene& s = rs->scene();
      const Pose pose = evaluatePose(s.animation, t, kAllAnimations);
      EXPECT_EQ(testsupport::verticesOutsideBounds(s, pose), 0u) << file << " at " << t << " s";
    }
  }
}

TEST_F(GpuDeform, SetTimeRefusesWhatIsNotATime) {
  std::shared_ptr<RenderScene> rs = RenderScene::load(asset("SimpleSkin/SimpleSkin.gltf"));
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      rs->setTime(bad);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const RuntimeError& e) {
      EXPECT_NE(std::string(e.what()).find("RenderScene::setTime: the time must be a finite number of seconds"),
                std::string::npos)
          << e.what();
    }
  }
  try {
    rs->setTime(1.0, 7);
    ADD_FAILURE() << "no error for animation 7";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("RenderScene::setTime: no animation 7 (the scene has 1)"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(rs->time(), 0.0);  // unchanged
  rs->setTime(-0.5);           // negative clocks loop (loopTime)
  EXPECT_EQ(rs->time(), -0.5);
}

// Model no more than a scene needs: a static scene neither deforms nor
// uploads, binds or writes anything for it, frame after frame.
TEST_F(GpuDeform, AStaticSceneUploadsNothingForAnimation) {
  std::shared_ptr<RenderScene> rs = RenderScene::load(asset("Box/Box.glb"));
  GpuScene& gpu = rs->gpu();
  EXPECT_FALSE(GpuScene::sceneDeforms(rs->scene()));
  EXPECT_FALSE(gpu.deforms());
  FrameMotion m;
  for (uint64_t f = 1; f <= 3; ++f) {
    rs->setTime(double(f) * 0.1);
    m.frame = f;
    m.prevViewProj = gpu.updateFrame({64, 64}, rs->scene().camera, m);
  }
  EXPECT_EQ(gpu.deformationBytes(), 0u);
  EXPECT_EQ(gpu.poseBytes(), 0u);
  // And an animated one writes only what moved: a still pose writes nothing more.
  std::shared_ptr<RenderScene> skin = RenderScene::load(asset("SimpleSkin/SimpleSkin.gltf"));
  GpuScene& g = skin->gpu();
  EXPECT_TRUE(g.deforms());
  EXPECT_GT(g.deformationBytes(), 0u);
  FrameMotion k;
  for (uint64_t f = 1; f <= 4; ++f) {
    skin->setTime(1.0);
    k.frame = f;
    k.prevViewProj = g.updateFrame({64, 64}, skin->scene().camera, k);
  }
  const uint64_t still = g.poseBytes();
  skin->setTime(1.0);
  k.frame = 5;
  g.updateFrame({64, 64}, skin->scene().camera, k);
  EXPECT_EQ(g.poseBytes(), still);
  skin->setTime(2.25);
  k.frame = 6;
  g.updateFrame({64, 64}, skin->scene().camera, k);
  std::printf("[ measure  ] SimpleSkin: %llu B of influences/deltas once, %llu B of pose for a moved frame\n",
              (unsigned long long)g.deformationBytes(), (unsigned long long)(g.poseBytes() - still));
  EXPECT_GT(g.poseBytes(), still);
}

// The picture: RecursiveSkeletons at 0.75 s through the default pipeline
// (geometry pass), forward.json (forward pass) and deferred-pbr-shadows.json
// (shadow maps), where scene.vert deforms, equals the same scene with every
// primitive replaced by its CPU-deformed vertices drawn as a static mesh
// (deformPrimitive, identity transform, no animation; the animated scene's
// bounds, so that shadow fitting is the same): max diff <= 2/255. And it
// differs from the rest pose (the skins bend: no longer straight bars) by far more.
namespace {
// Renders RecursiveSkeletons posed at 0.75 s and the CPU-baked scene with
// `pipeline`; with `rest`, the rest pose too (which must differ).
void imageMatchesBaked(const char* pipeline, bool rest) {
  const std::string file = asset("RecursiveSkeletons/RecursiveSkeletons.glb");
  const double t = 0.75;
  auto render = [](const std::string& pipeline, std::shared_ptr<RenderScene> scene, const Camera& cam) {
    RendererOptions options;
    options.size = {96, 64};
    Diagnostics diags;
    auto r = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + pipeline, options, diags);
    EXPECT_TRUE(r) << pipeline;
    r->setScene(std::move(scene));
    r->setCamera(cam);
    r->render();
    return r->readOutputRGBA8();
  };
  auto maxDiff = [](const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    if (a.size() != b.size()) return 256;
    int worst = 0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
    return worst;
  };
  std::shared_ptr<RenderScene> animated = RenderScene::load(file);
  const Camera cam = animated->scene().camera;
  std::shared_ptr<RenderScene> atRest = rest ? RenderScene::load(file) : nullptr;
  animated->setTime(t);

  Scene baked = loadSceneAny(file);
  const Pose pose = evaluatePose(baked.animation, t, kAllAnimations);
  std::vector<MeshData> meshes;
  for (size_t i = 0; i < baked.primitives.size(); ++i) {
    const DeformedVertices d = deformPrimitive(baked, pose, i);
    MeshData m = baked.meshes[size_t(baked.primitives[i].mesh)];
    m.positions = d.positions;
    m.normals = d.normals;
    if (!d.tangents.empty()) m.tangents = d.tangents;
    m.influences.clear();
    m.morphTargets.clear();
    m.updateBounds();
    meshes.push_back(std::move(m));
    baked.primitives[i].mesh = int(i);
    baked.primitives[i].node = -1;
    baked.primitives[i].transform = glm::mat4(1.0f);
    baked.primitives[i].bounds = animated->scene().primitives[i].bounds;
  }
  baked.meshes = std::move(meshes);
  baked.animation = SceneAnimation{};
  std::shared_ptr<RenderScene> reference = RenderScene::fromScene(std::move(baked));
  const std::vector<uint8_t> posed = render(pipeline, animated, cam), want = render(pipeline, reference, cam);
  const int diff = maxDiff(posed, want);
  std::printf("[ measure  ] RecursiveSkeletons at %.2f s, %s, vs CPU-deformed static mesh: max diff %d/255\n", t,
              pipeline, diff);
  EXPECT_LE(diff, 2) << pipeline;
  if (!rest) return;
  const int fromRest = maxDiff(render(pipeline, atRest, cam), want);
  std::printf("[ measure  ] the rest pose vs it: %d/255\n", fromRest);
  EXPECT_GE(fromRest, 64) << pipeline;
}
}  // namespace

TEST_F(GpuDeform, RecursiveSkeletonsImageMatchesCpuDeformedGeometry) { imageMatchesBaked("default.json", true); }
TEST_F(GpuDeform, RecursiveSkeletonsForwardImageMatchesCpuDeformedGeometry) { imageMatchesBaked("forward.json", false); }
TEST_F(GpuDeform, RecursiveSkeletonsShadowedImageMatchesCpuDeformedGeometry) {
  imageMatchesBaked("deferred-pbr-shadows.json", false);
}
