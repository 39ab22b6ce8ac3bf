// Picking through the public API (Renderer::requestPick / pickResult,
// RendererOptions::picking): the object_id target is absent unless asked
// for, present when the caller or the pipeline asks; pixels over known
// cubes answer those cubes a frame late, the background answers nothing, a
// moved object is found at its new place, a removed one is never returned;
// misuse and pipelines without ids answer clearly.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/error.h"
#include "rgraph/renderer.h"
#include "renderer_util.h"
#include "test_support.h"

namespace {
using namespace rgraph;
using testsupport::errorOf;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";
const std::string kForward = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/forward.json";
constexpr Extent kSize{96, 64};

// default.json's G-buffer with ids asked for by the pipeline itself.
const std::string kIdsInConfig = testsupport::gbufferPipeline({"object_id", "ids", "rg32ui"});

glm::mat4 at(float x, float y = 0.0f) { return glm::translate(glm::mat4(1.0f), {x, y, 0.0f}); }

// Cubes (edge 1) at the given x (testsupport::cubesScene).
Scene cubes(const std::vector<float>& xs) {
  std::vector<glm::vec3> places;
  for (float x : xs) places.emplace_back(x, 0.0f, 0.0f);
  return testsupport::cubesScene(places);
}

// The pixel (column, row from the top) where world point `p` lands.
glm::uvec2 pixelOf(const Camera& cam, const glm::vec3& p) {
  const glm::vec4 clip = cam.viewProjection(float(kSize.width) / float(kSize.height)) * glm::vec4(p, 1.0f);
  const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
  return {unsigned(uv.x * float(kSize.width)), unsigned((1.0f - uv.y) * float(kSize.height))};
}

std::unique_ptr<Renderer> makeRenderer(const std::string& pipeline, bool picking,
                                       std::shared_ptr<RenderScene> scene) {
  RendererOptions options;
  options.size = kSize;
  options.picking = picking;
  return testsupport::makeRenderer(pipeline, options, std::move(scene), "ids.json");
}

// Asks about `px`, renders the frame that reads it and one more, and takes
// the answer without waiting (it must be in by then on any device that
// finished the frames: the reads are waited for only by that render()).
std::optional<PickResult> pickAt(Renderer& r, glm::uvec2 px) {
  r.requestPick(px.x, px.y);
  r.render();
  const std::optional<PickResult> early = r.pickResult();
  r.render();
  std::optional<PickResult> answer = r.pickResult(/*wait=*/true);
  // Read from the frame rendered right after the request (frameIndex() counting).
  EXPECT_TRUE(!early || early->frame + 2 == r.frameIndex()) << "early answer of frame " << early->frame;
  if (answer) EXPECT_EQ(answer->frame + 2, r.frameIndex());
  return answer;
}

// The resources of the plan with an integer format, and the bytes it allocates.
std::vector<std::string> integerResources(const Plan& plan) {
  std::vector<std::string> out;
  for (const auto& res : plan.resources) {
    if (!res.physical.valid()) continue;
    if (formatInfo(plan.physical[res.physical.value()].format).isInteger) out.push_back(res.name);
  }
  return out;
}

size_t attachmentsOf(const Plan& plan, const std::string& pass) {
  for (size_t i = 0; i < plan.passes.size(); ++i)
    if (plan.passes[i].name == pass)
      return size_t(std::count_if(plan.bindings[i].begin(), plan.bindings[i].end(),
                                  [](const BoundUse& u) { return u.access == Access::color_attachment; }));
  return 0;
}

class RendererPick : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

// Absent by default: no integer texture, no extra attachment on the geometry
// pass; with picking: one rg32ui "object_id" of 8 bytes a pixel more.
TEST_F(RendererPick, ObjectIdsAreAbsentUnlessAsked) {
  auto scene = RenderScene::fromScene(cubes({-1.2f, 1.2f}));
  auto plain = makeRenderer(kDefault, false, scene);
  auto picking = makeRenderer(kDefault, true, scene);
  ASSERT_TRUE(plain && picking);
  plain->render();
  picking->render();
  const Plan& a = plain->plan();
  const Plan& b = picking->plan();
  EXPECT_TRUE(integerResources(a).empty());
  EXPECT_EQ(integerResources(b), std::vector<std::string>{"object_id"});
  EXPECT_EQ(attachmentsOf(b, "gbuffer"), attachmentsOf(a, "gbuffer") + 1);
  EXPECT_EQ(b.naiveBytes, a.naiveBytes + uint64_t(kSize.width) * kSize.height * 8);
  EXPECT_FALSE(plain->pipeline().params[0].getBool("object_id"));
  const auto& notes = picking->adaptNotes();
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(),
                          [](const std::string& n) { return n.find("object ids") != std::string::npos; }));
}

TEST_F(RendererPick, PixelsOverCubesAnswerThoseCubesAndTheBackgroundNothing) {
  auto scene = RenderScene::fromScene(cubes({-1.2f, 1.2f}));
  const std::vector<InstanceId> ids = scene->instances();
  auto r = makeRenderer(kDefault, true, scene);
  ASSERT_TRUE(r);
  r->render();
  const Camera& cam = scene->scene().camera;
  for (size_t i = 0; i < 2; ++i) {
    const glm::uvec2 px = pixelOf(cam, {i == 0 ? -1.2f : 1.2f, 0.0f, 0.5f});
    const std::optional<PickResult> p = pickAt(*r, px);
    ASSERT_TRUE(p) << "cube " << i;
    EXPECT_EQ(p->instance, ids[i]) << "cube " << i << " at (" << px.x << ", " << px.y << "): got instance "
                                   << p->instance.value;
    EXPECT_EQ(p->x, px.x);
    EXPECT_EQ(p->y, px.y);
    EXPECT_TRUE(p->problem.empty()) << p->problem;
    EXPECT_LT(p->triangle, 12u);  // a cube's triangles
  }
  // Top-left origin: the top row above the cubes, and a corner, are background.
  for (glm::uvec2 px : {glm::uvec2{kSize.width / 2, 1}, glm::uvec2{0, 0}, glm::uvec2{kSize.width - 1, kSize.height - 1}}) {
    const std::optional<PickResult> p = pickAt(*r, px);
    ASSERT_TRUE(p);
    EXPECT_FALSE(p->instance) << "(" << px.x << ", " << px.y << ") got instance " << p->instance.value;
  }
  // The top face of the left cube seen from above its centre (a pixel above
  // the centre row): the same object, found counting rows from the top.
  const glm::uvec2 upper = pixelOf(cam, {-1.2f, 0.4f, 0.5f});
  const glm::uvec2 lower = pixelOf(cam, {-1.2f, -0.4f, 0.5f});
  ASSERT_LT(upper.y, lower.y);
  EXPECT_EQ(pickAt(*r, upper)->instance, ids[0]);
  EXPECT_EQ(pickAt(*r, lower)->instance, ids[0]);
}

// setTransform: the frame after the move answers at the new place, and the
// old place is background; a removed object is never returned.
TEST_F(RendererPick, MovedObjectsAreFoundWhereTheyAreAndRemovedOnesNever) {
  auto scene = RenderScene::fromScene(cubes({-1.2f, 1.2f}));
  const std::vector<InstanceId> ids = scene->instances();
  auto r = makeRenderer(kDefault, true, scene);
  ASSERT_TRUE(r);
  r->render();
  const Camera& cam = scene->scene().camera;
  const glm::uvec2 left = pixelOf(cam, {-1.2f, 0.0f, 0.5f});
  const glm::uvec2 middle = pixelOf(cam, {0.0f, 0.0f, 0.5f});
  EXPECT_FALSE(pickAt(*r, middle)->instance);
  scene->setTransform(ids[1], at(0.0f));
  EXPECT_EQ(pickAt(*r, middle)->instance, ids[1]);
  // Asked before the move, read from the frame after it: the ids of that frame.
  scene->setTransform(ids[1], at(1.2f));
  EXPECT_FALSE(pickAt(*r, middle)->instance);
  scene->removeInstance(ids[0]);
  EXPECT_FALSE(pickAt(*r, left)->instance);
  // Removed between the frame that was read and the answer: not returned.
  const glm::uvec2 right = pixelOf(cam, {1.2f, 0.0f, 0.5f});
  r->requestPick(right.x, right.y);
  r->render();
  scene->removeInstance(ids[1]);
  const std::optional<PickResult> gone = r->pickResult(/*wait=*/true);
  ASSERT_TRUE(gone);
  EXPECT_FALSE(gone->instance) << "removed instance " << ids[1].value << " returned";
  EXPECT_TRUE(gone->problem.empty());
}

// The pipeline may ask itself (the geometry pass's "object_id"), picking off.
TEST_F(RendererPick, APipelineThatWritesIdsIsPickedWithoutTheOption) {
  auto scene = RenderScene::fromScene(cubes({-1.2f, 1.2f}));
  auto r = makeRenderer(kIdsInConfig, false, scene);
  ASSERT_TRUE(r);
  r->render();
  const std::optional<PickResult> p = pickAt(*r, pixelOf(scene->scene().camera, {1.2f, 0.0f, 0.5f}));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->instance, scene->instances()[1]);
}

TEST_F(RendererPick, MisuseAndPipelinesWithoutIdsAnswerClearly) {
  auto scene = RenderScene::fromScene(cubes({0.0f}));
  auto r = makeRenderer(kDefault, false, scene);
  ASSERT_TRUE(r);
  // Nothing asked, no frame: no answer.
  EXPECT_FALSE(r->pickResult());
  EXPECT_EQ(errorOf([&] { r->requestPick(kSize.width, 0); }),
            "Renderer::requestPick: pixel (96, 0) is outside the output (96x64, counted from its top-left corner)");
  EXPECT_NE(errorOf([&] { r->requestPick(0, kSize.height); }).find("outside the output"), std::string::npos);
  // Asked before any frame: pending until one is drawn.
  r->requestPick(10, 10);
  EXPECT_FALSE(r->pickResult(/*wait=*/true));
  r->render();
  std::optional<PickResult> p = r->pickResult();
  ASSERT_TRUE(p);
  EXPECT_FALSE(p->instance);
  EXPECT_NE(p->problem.find("the pipeline writes no object ids"), std::string::npos) << p->problem;
  // A forward pipeline has no pass that writes ids: picking asks in vain.
  auto fwd = makeRenderer(kForward, true, scene);
  ASSERT_TRUE(fwd);
  fwd->requestPick(48, 32);
  fwd->render();
  p = fwd->pickResult();
  ASSERT_TRUE(p);
  EXPECT_NE(p->problem.find("RendererOptions::picking"), std::string::npos) << p->problem;
  // A new scene forgets a pick in flight and an answer: their ids were the old scene's.
  fwd->requestPick(48, 32);
  fwd->setScene(RenderScene::fromScene(cubes({0.0f})));
  fwd->render();
  EXPECT_FALSE(fwd->pickResult(/*wait=*/true));
  auto ids = makeRenderer(kDefault, true, scene);
  ASSERT_TRUE(ids);
  ids->requestPick(48, 32);
  ids->render();
  ids->setScene(RenderScene::fromScene(cubes({0.0f})));
  EXPECT_FALSE(ids->pickResult(/*wait=*/true));
}

}  // namespace
