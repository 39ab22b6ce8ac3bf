// Scene objects through the public API (RenderScene's instances,
// rgraph/renderer.h): moved, added, hidden and removed between frames with
// no rebuild, no upload and no GL object, drawn as a scene built with them
// in place, with their motion in the velocity target; and every call a
// caller can get wrong refused by name, changing nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "renderer_util.h"
#include "test_support.h"

namespace {
using namespace rgraph;
using testsupport::cubesScene;
using testsupport::errorOf;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";
// The G-buffer with motion vectors under a jittered camera, as
// deferred-taa.json's geometry pass writes them (without the taa plugin).
const std::string kVelocityPipeline = testsupport::gbufferPipeline({"velocity", "gVelocity", "rg16f", 8, "rgba32f"});
constexpr Extent kSize{96, 64};

glm::mat4 at(float x, float y = 0.0f, float z = 0.0f) { return glm::translate(glm::mat4(1.0f), {x, y, z}); }

std::unique_ptr<Renderer> makeRenderer(const std::string& pipeline, std::shared_ptr<RenderScene> scene) {
  RendererOptions options;
  options.size = kSize;
  return testsupport::makeRenderer(pipeline, options, std::move(scene), "velocity.json");
}

std::vector<uint8_t> frame(Renderer& r) {
  r.render();
  return r.readOutputRGBA8();
}

int maxDiff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  if (a.size() != b.size()) return 256;
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  return worst;
}

// The pixel (column, row from the top) where world point `p` lands.
glm::ivec2 pixelOf(const Camera& cam, const glm::vec3& p) {
  const glm::vec4 clip = cam.viewProjection(float(kSize.width) / float(kSize.height)) * glm::vec4(p, 1.0f);
  const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
  return {int(uv.x * float(kSize.width)), int((1.0f - uv.y) * float(kSize.height))};
}

glm::ivec3 rgb(const std::vector<uint8_t>& img, glm::ivec2 px) {
  const size_t i = (size_t(px.y) * kSize.width + size_t(px.x)) * 4;
  return {img[i], img[i + 1], img[i + 2]};
}

class RendererInstances : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

// A loaded scene's primitives are objects: moving one draws what a scene
// built with it there draws (within 1/255), with no rebuild, no upload and
// no GL object created.
TEST_F(RendererInstances, AMovedObjectDrawsAsASceneBuiltWithItThere) {
  auto scene = RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}, {1.0f, 0, 0}}));
  ASSERT_EQ(scene->instances().size(), 2u);
  auto r = makeRenderer(kDefault, scene);
  const std::vector<uint8_t> before = frame(*r);
  frame(*r);
  const int64_t created = gl::createdObjectsTotal();

  const InstanceId moving = scene->instances()[0];
  scene->setTransform(moving, at(-0.2f, 0.6f));
  const std::vector<uint8_t> moved = frame(*r);
  EXPECT_EQ(gl::createdObjectsTotal(), created) << "GL objects created by a steady frame with a move";
  EXPECT_EQ(r->builds(), 1u);
  EXPECT_EQ(scene->uploadCount(), 1u);

  auto reference = makeRenderer(kDefault, RenderScene::fromScene(cubesScene({{-0.2f, 0.6f, 0.0f}, {1.0f, 0, 0}})));
  const std::vector<uint8_t> expected = frame(*reference);
  const int diff = maxDiff(moved, expected);
  std::printf("[ measure  ] moved object against the scene built with it there: max diff %d/255\n", diff);
  EXPECT_LE(diff, 1);

  // Where it was is background now, and where it went is cube.
  const Camera& cam = scene->scene().camera;
  const glm::ivec3 background = rgb(before, {1, 1});
  EXPECT_NE(rgb(before, pixelOf(cam, {-1.2f, 0.0f, 0.5f})), background);
  EXPECT_EQ(rgb(moved, pixelOf(cam, {-1.2f, 0.0f, 0.5f})), background);
  EXPECT_NE(rgb(moved, pixelOf(cam, {-0.2f, 0.6f, 0.5f})), background);
}

// Only what changed is written: a still frame writes nothing into the
// scene's Objects buffer, a moved object its own entry (its model, previous
// model and normal matrices: 3 mat4s), and the frame after it stops the same
// entry once more (its previous matrix catches up).
TEST_F(RendererInstances, OnlyAMovedObjectsEntryIsWritten) {
  auto scene = RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}, {0.0f, 0, 0}, {1.2f, 0, 0}}));
  auto r = makeRenderer(kDefault, scene);
  frame(*r);
  GpuScene& gpu = scene->gpu();
  auto written = [&] {
    const uint64_t before = gpu.objectBytes();
    frame(*r);
    return gpu.objectBytes() - before;
  };
  constexpr uint64_t kEntry = 3 * sizeof(glm::mat4);
  EXPECT_EQ(written(), 0u) << "a still frame";
  scene->setTransform(scene->instances()[1], at(0.0f, 0.3f));
  EXPECT_EQ(written(), kEntry) << "the moved object's entry";
  EXPECT_EQ(written(), kEntry) << "its previous matrix, the frame after";
  EXPECT_EQ(written(), 0u);
  EXPECT_EQ(scene->uploadCount(), 1u);
}

// The velocity target holds a moved object's motion (uv_now - uv_prev): its
// front face at depth 4.5 moved 0.2 along x moves 0.2 / (2 * 4.5 * tan(22.5
// deg) * aspect) in u, nothing in v; the object left alone and the
// background hold none. A cut would have zeroed it all (and reset TAA).
TEST_F(RendererInstances, TheVelocityTargetHoldsAMovedObjectsMotion) {
  auto scene = RenderScene::fromScene(cubesScene({{-0.4f, 0, 0}, {1.4f, 0, 0}}));
  auto r = makeRenderer(kVelocityPipeline, scene);
  frame(*r);
  frame(*r);
  const InstanceId moving = scene->instances()[0];
  const float dx = 0.2f;
  scene->setTransform(moving, at(-0.4f + dx));
  frame(*r);
  EXPECT_EQ(r->builds(), 1u);
  const std::vector<float> v = r->readResourceRGBA32F("gVelocity");
  ASSERT_EQ(v.size(), size_t(kSize.width) * kSize.height * 4);
  const Camera& cam = scene->scene().camera;
  auto velocity = [&](glm::ivec2 px) { return glm::vec2(v[(size_t(px.y) * kSize.width + px.x) * 4], v[(size_t(px.y) * kSize.width + px.x) * 4 + 1]); };
  const float aspect = float(kSize.width) / float(kSize.height);
  const float expectedU = dx / (2.0f * 4.5f * std::tan(glm::radians(22.5f)) * aspect);
  const glm::vec2 got = velocity(pixelOf(cam, {-0.4f + dx, 0.1f, 0.5f}));
  std::printf("[ measure  ] moved object's velocity (%.5f, %.5f) UV, expected (%.5f, 0)\n", got.x, got.y, expectedU);
  EXPECT_NEAR(got.x, expectedU, 1e-3f);
  EXPECT_NEAR(got.y, 0.0f, 1e-3f);
  EXPECT_EQ(velocity(pixelOf(cam, {1.4f, 0.1f, 0.5f})), glm::vec2(0.0f)) << "the object left alone";
  EXPECT_EQ(velocity({1, 1}), glm::vec2(0.0f)) << "the background";

  // The next frame without a move: no motion left.
  frame(*r);
  const std::vector<float> still = r->readResourceRGBA32F("gVelocity");
  const glm::ivec2 px = pixelOf(cam, {-0.4f + dx, 0.1f, 0.5f});
  EXPECT_EQ(glm::vec2(still[(size_t(px.y) * kSize.width + px.x) * 4], still[(size_t(px.y) * kSize.width + px.x) * 4 + 1]),
            glm::vec2(0.0f));
}

// Hidden and removed objects are not drawn: the image is the scene's without
// them. Other ids stay valid after a removal; the removed one is refused.
TEST_F(RendererInstances, HiddenAndRemovedObjectsAreNotDrawn) {
  auto scene = RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}, {0.0f, 0, 0}, {1.2f, 0, 0}}));
  auto r = makeRenderer(kDefault, scene);
  const std::vector<uint8_t> all = frame(*r);
  auto without = makeRenderer(kDefault, RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}, {1.2f, 0, 0}})));
  const std::vector<uint8_t> expected = frame(*without);
  ASSERT_GT(maxDiff(all, expected), 10);

  const std::vector<InstanceId> ids = scene->instances();
  const int64_t created = gl::createdObjectsTotal();
  scene->setVisible(ids[1], false);
  EXPECT_FALSE(scene->visible(ids[1]));
  EXPECT_LE(maxDiff(frame(*r), expected), 1);
  scene->setVisible(ids[1], true);
  EXPECT_LE(maxDiff(frame(*r), all), 1);

  scene->removeInstance(ids[1]);
  EXPECT_LE(maxDiff(frame(*r), expected), 1);
  EXPECT_FALSE(scene->contains(ids[1]));
  EXPECT_EQ(scene->primitiveIndex(ids[2]), 1u);
  scene->setTransform(ids[2], at(1.2f));  // still valid
  EXPECT_NE(errorOf([&] { scene->setTransform(ids[1], at(0.0f)); }).find("no instance " + std::to_string(ids[1].value)),
            std::string::npos);
  EXPECT_EQ(gl::createdObjectsTotal(), created);
  EXPECT_EQ(r->builds(), 1u);
}

// Removing an object keeps the others' GPU data in step: an
// EXT_mesh_gpu_instancing primitive after the removed one still draws all its
// instances (what a scene built without the removed one draws).
TEST_F(RendererInstances, RemovingAnObjectKeepsTheOthersInstancing) {
  auto instanced = [](bool withFirst) {
    Scene s = cubesScene(withFirst ? std::vector<glm::vec3>{{-1.5f, 0.8f, 0.0f}, {0.0f, 0.0f, 0.0f}}
                              : std::vector<glm::vec3>{{0.0f, 0.0f, 0.0f}});
    Primitive& p = s.primitives.back();
    p.instances = {at(-1.2f, -0.5f), at(0.0f, 0.2f), at(1.2f, -0.5f)};
    p.transform = glm::scale(glm::mat4(1.0f), glm::vec3(0.6f));
    p.bounds = p.worldBounds(s.meshes[0].bounds);
    return s;
  };
  auto scene = RenderScene::fromScene(instanced(true));
  auto r = makeRenderer(kDefault, scene);
  frame(*r);
  scene->removeInstance(scene->instances().front());
  const std::vector<uint8_t> after = frame(*r);
  auto reference = makeRenderer(kDefault, RenderScene::fromScene(instanced(false)));
  EXPECT_LE(maxDiff(after, frame(*reference)), 1);
  // And it moves as a whole (transform * each instance).
  const InstanceId group = scene->instances().front();
  scene->setTransform(group, at(0.0f, 0.5f) * glm::scale(glm::mat4(1.0f), glm::vec3(0.6f)));
  EXPECT_NE(maxDiff(frame(*r), after), 0);
  EXPECT_EQ(r->builds(), 1u);
}

// A loaded scene (a glTF file) keeps drawing as it did; its primitives are objects.
TEST_F(RendererInstances, ALoadedScenesPrimitivesAreObjects) {
  auto scene = RenderScene::load(std::string(RGRAPH_ASSETS_DIR) + "/gltf/Box/Box.glb");
  ASSERT_EQ(scene->instances().size(), scene->scene().primitives.size());
  ASSERT_FALSE(scene->instances().empty());
  auto r = makeRenderer(kDefault, scene);
  const std::vector<uint8_t> still = frame(*r);
  EXPECT_EQ(maxDiff(frame(*r), still), 0);
  const InstanceId box = scene->instances().front();
  EXPECT_EQ(scene->instanceAt(0), box);
  scene->setTransform(box, glm::rotate(scene->transform(box), 0.3f, glm::vec3(0.0f, 1.0f, 0.0f)));
  EXPECT_GT(maxDiff(frame(*r), still), 10);
  EXPECT_EQ(r->builds(), 1u);
}

// A mesh made in code is uploaded once and shared: two objects drawing it
// draw what a scene built with them draws; the scene's upload count stays 1.
TEST_F(RendererInstances, AMeshMadeInCodeIsUploadedOnceAndShared) {
  auto scene = RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}}));
  auto r = makeRenderer(kDefault, scene);
  frame(*r);
  const uint64_t geometry = scene->gpu().geometryBytes();
  MeshData wedge;
  wedge.name = "wedge";
  wedge.positions = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.0f, 0.5f, 0.0f}};
  wedge.indices = {0, 1, 2};
  const size_t mesh = scene->addMesh(wedge);
  const uint64_t meshBytes = scene->gpu().geometryBytes() - geometry;
  EXPECT_GT(meshBytes, 0u);
  const InstanceId a = scene->addInstance(mesh, 0, at(0.3f), "a");
  const InstanceId b = scene->addInstance(mesh, 0, at(1.3f, 0.2f), "b");
  const std::vector<uint8_t> drawn = frame(*r);
  const int64_t created = gl::createdObjectsTotal();
  scene->setTransform(a, at(0.4f));
  frame(*r);
  scene->setTransform(a, at(0.3f));
  const std::vector<uint8_t> back = frame(*r);
  EXPECT_EQ(gl::createdObjectsTotal(), created);
  EXPECT_EQ(scene->gpu().geometryBytes() - geometry, meshBytes) << "geometry uploaded again";
  EXPECT_EQ(scene->uploadCount(), 1u);
  EXPECT_EQ(r->builds(), 1u) << "objects that grow the scene's bounds (no light markers to resize)";
  EXPECT_EQ(maxDiff(drawn, back), 0);
  EXPECT_EQ(scene->scene().primitives[scene->primitiveIndex(b)].mesh, int(mesh));

  Scene built = cubesScene({{-1.2f, 0, 0}});
  MeshData filled = scene->scene().meshes[mesh];  // as addMesh completed it (normals, uv0, tangents)
  built.meshes.push_back(filled);
  for (auto [x, y] : {std::pair{0.3f, 0.0f}, std::pair{1.3f, 0.2f}}) {
    Primitive p;
    p.mesh = 1;
    p.material = 0;
    p.transform = at(x, y);
    p.bounds = p.worldBounds(filled.bounds);
    built.primitives.push_back(p);
  }
  auto reference = makeRenderer(kDefault, RenderScene::fromScene(built));
  EXPECT_LE(maxDiff(drawn, frame(*reference)), 1);
}

// Material values per object: the object gets its own copy, others keep
// theirs; the edit shows in the image.
TEST_F(RendererInstances, MaterialValuesArePerObject) {
  auto scene = RenderScene::fromScene(cubesScene({{-1.2f, 0, 0}, {1.2f, 0, 0}}));
  auto r = makeRenderer(kDefault, scene);
  const std::vector<uint8_t> before = frame(*r);
  const std::vector<InstanceId> ids = scene->instances();
  MaterialParameters green = scene->materialParameters(ids[0]);
  green.baseColorFactor = glm::vec4(0.1f, 0.9f, 0.1f, 1.0f);
  scene->setMaterialParameters(ids[0], green);
  EXPECT_EQ(scene->materialParameters(ids[0]).baseColorFactor, green.baseColorFactor);
  EXPECT_EQ(scene->materialParameters(ids[1]).baseColorFactor, glm::vec4(0.8f, 0.5f, 0.3f, 1.0f));
  const std::vector<uint8_t> after = frame(*r);
  const Camera& cam = scene->scene().camera;
  const glm::ivec3 was = rgb(before, pixelOf(cam, {-1.2f, 0.0f, 0.5f})), now = rgb(after, pixelOf(cam, {-1.2f, 0.0f, 0.5f}));
  EXPECT_LT(now.r + 40, was.r) << "the recoloured object";
  EXPECT_GT(now.g, was.g + 20) << "the recoloured object";
  EXPECT_EQ(rgb(after, pixelOf(cam, {1.2f, 0.0f, 0.5f})), rgb(before, pixelOf(cam, {1.2f, 0.0f, 0.5f})));
  // A second edit rewrites the same copy: the scene does not grow.
  const size_t materials = scene->scene().materials.size();
  green.baseColorFactor.r = 0.5f;
  scene->setMaterialParameters(ids[0], green);
  EXPECT_EQ(scene->scene().materials.size(), materials);
}

// Every call a caller can get wrong: RuntimeError naming the object and the
// value, and nothing changed.
TEST_F(RendererInstances, MisuseIsRefusedByNameAndChangesNothing) {
  auto scene = RenderScene::fromScene(cubesScene({{0.0f, 0, 0}}));
  const InstanceId id = scene->instances()[0];
  const glm::mat4 before = scene->transform(id);
  const uint64_t version = scene->instancesVersion();
  auto refused = [&](const std::function<void()>& call, const std::string& want) {
    const std::string error = errorOf(call);
    EXPECT_NE(error.find(want), std::string::npos) << "got: " << error;
  };
  glm::mat4 nan = at(1.0f);
  nan[3].x = std::nanf("");
  refused([&] { scene->setTransform(id, nan); }, "cubes: RenderScene::setTransform: instance 1 ('cube0'): transform: column 3 (nan, 0, 0, 1) is not finite");
  refused([&] { scene->setTransform(id, glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f))); }, "determinant 0");
  refused([&] { scene->setTransform(id, at(2e15f)); }, "exceed +-1e+15 units");
  refused([&] { scene->setTransform(InstanceId{99}, at(0.0f)); }, "RenderScene::setTransform: no instance 99");
  refused([&] { scene->setMaterial(id, 5); }, "instance 1 ('cube0'): material 5 is out of range (the scene has 1)");
  refused([&] { scene->addInstance(0, 3, at(0.0f), "crate"); }, "instance 2 ('crate'): material 3 is out of range");
  refused([&] { scene->addInstance(7, 0, at(0.0f)); }, "mesh 7 is out of range (the scene has 1)");
  refused([&] { scene->setMaterialParameters(id, MaterialParameters{glm::vec4(1.0f), 1.5f}); },
          "instance 1 ('cube0'): metallicFactor: 1.5 must be in 0..1");
  refused([&] { scene->setMaterialParameters(id, MaterialParameters{glm::vec4(1.0f), 1.0f, 1.0f, glm::vec3(-1.0f)}); },
          "emissiveFactor: (-1, -1, -1) must be finite and >= 0");
  MeshData bad;
  bad.name = "bad";
  bad.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad.normals = {{0, 0, 1}, {0, 0, 1}};
  bad.indices = {0, 1, 2};
  refused([&] { scene->addMesh(bad); }, "RenderScene::addMesh: mesh 'bad': normals: 2 for 3 positions");
  bad.normals.clear();
  bad.indices = {0, 1, 3};
  refused([&] { scene->addMesh(bad); }, "indices[2]: 3 is not below the 3 positions");
  bad.indices = {0, 1};
  refused([&] { scene->addMesh(bad); }, "indices: 2 is not a multiple of 3");
  Material shiny;
  shiny.roughnessFactor = -0.5f;
  refused([&] { scene->addMaterial(shiny); }, "RenderScene::addMaterial: material 1: roughnessFactor: -0.5 must be in 0..1");
  refused([&] { scene->removeInstance(InstanceId{42}); }, "no instance 42");

  EXPECT_EQ(scene->transform(id), before);
  EXPECT_EQ(scene->instances().size(), 1u);
  EXPECT_EQ(scene->scene().meshes.size(), 1u);
  EXPECT_EQ(scene->scene().materials.size(), 1u);
  EXPECT_EQ(scene->instancesVersion(), version);
  EXPECT_EQ(scene->scene().primitives[0].material, 0);
}

// An object added with a blended material to a scene that had none adapts
// the pipeline again (once), as a first point light does; moving it then
// does not.
TEST_F(RendererInstances, AnEditThatChangesWhatTheSceneNeedsAdaptsOnce) {
  auto scene = RenderScene::fromScene(cubesScene({{0.0f, 0, 0}}));
  auto r = makeRenderer(kDefault, scene);
  frame(*r);
  ASSERT_EQ(r->builds(), 1u);
  Material glass;
  glass.alphaMode = AlphaMode::blend;
  glass.baseColorFactor = glm::vec4(0.2f, 0.4f, 1.0f, 0.5f);
  const InstanceId pane = scene->addInstance(0, scene->addMaterial(glass), at(0.5f, 0.0f, 1.0f), "pane");
  frame(*r);
  EXPECT_EQ(r->builds(), 2u);
  scene->setTransform(pane, at(0.6f, 0.0f, 1.0f));
  frame(*r);
  EXPECT_EQ(r->builds(), 2u);
}

}  // namespace
