// rgraph view's resource inspector without a window: the copy made right
// after a resource's last write in the frame, even when its memory is aliased
// and overwritten later in the frame; the value mapping its display shader
// mirrors, checked on the CPU and against that shader.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "rgraph/renderer.h"
#include "test_support.h"
#include "view_panels.h"
#include "view_panels_map.h"
#include "view_test_util.h"

namespace {
using namespace rgraph;
using view::ResourceInspector;
using view::ValueMapping;
using viewtest::kAliasing;

const float kFill[4] = {0.25f, 0.5f, 0.75f, 1.0f};
constexpr Extent kSize{48, 32};

class ViewInspector : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }

  std::unique_ptr<Renderer> make(const std::string& json) {
    RendererOptions options;
    options.size = kSize;
    Diagnostics diags;
    auto r = Renderer::fromJson(json, "aliasing.json", options, diags);
    EXPECT_TRUE(r) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
    return r;
  }
};

ResourceIndex findResourceIndex(const Plan& plan, const std::string& name) {
  for (size_t i = 0; i < plan.resources.size(); ++i)
    if (plan.resources[i].name == name) return ResourceIndex(uint32_t(i));
  return {};
}

bool allTexels(const std::vector<float>& rgba, const float (&v)[4]) {
  for (size_t i = 0; i < rgba.size(); ++i)
    if (rgba[i] != v[i % 4]) return false;
  return !rgba.empty();
}

TEST_F(ViewInspector, CaptureStepsComeFromThePlansWrites) {
  auto r = make(kAliasing);
  ASSERT_TRUE(r);
  const Plan& plan = r->plan();
  ASSERT_EQ(plan.order.size(), 5u);
  EXPECT_EQ(plan.resource(ResourceIndex(0)).physical, plan.resource(ResourceIndex(2)).physical)
      << "the test needs a and c aliased";
  EXPECT_EQ(ResourceInspector::captureStep(plan, "a"), StepIndex(0));
  EXPECT_EQ(ResourceInspector::captureStep(plan, "b"), StepIndex(1));
  EXPECT_EQ(ResourceInspector::captureStep(plan, "c"), StepIndex(3)) << "a resource: its last write";
  EXPECT_EQ(ResourceInspector::captureStep(plan, "c_2"), StepIndex(3));
  EXPECT_EQ(ResourceInspector::captureStep(plan, "output"), StepIndex(4));
  EXPECT_FALSE(ResourceInspector::captureStep(plan, "nope").valid());
  EXPECT_EQ(ResourceInspector::selectableNames(plan),
            (std::vector<std::string>{"a", "b", "c", "c_2", "output", "unused"}));
}

TEST_F(ViewInspector, AnAliasedTransientShowsWhatItHeldBeforeItsMemoryWasReused) {
  auto r = make(kAliasing);
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("a");
  EXPECT_EQ(inspector.capturedTexture(), 0u) << "nothing copied before a frame";
  r->render();
  ASSERT_NE(inspector.capturedTexture(), 0u);
  EXPECT_EQ(inspector.capturedExtent(), kSize);
  EXPECT_TRUE(allTexels(inspector.readCaptured(), kFill)) << "the copy holds a's fill";
  // a's memory now holds c_2 = c + (1 - b): reading it after the frame is not what a held.
  const std::vector<float> after = r->readResourceRGBA32F("a");
  EXPECT_FALSE(allTexels(after, kFill));
  EXPECT_NEAR(after[0], 0.125f + 0.75f, 1e-3f);
  const glm::vec4 texel = inspector.readCapturedTexel(5, 7);
  EXPECT_EQ(texel, glm::vec4(kFill[0], kFill[1], kFill[2], kFill[3]));
}

TEST_F(ViewInspector, AResourceNotOverwrittenLaterEqualsTheRenderersReadBack) {
  auto r = make(kAliasing);
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  for (const char* name : {"b", "c", "c_2"}) {
    inspector.select(name);
    r->render();
    EXPECT_EQ(inspector.readCaptured(), r->readResourceRGBA32F(name)) << name;
  }
}

TEST_F(ViewInspector, GBufferTargetsAndDepthOfTheDefaultPipelineAreCopiedOncePerFrame) {
  auto r = viewtest::defaultRenderer({96, 64});
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  for (const char* name : {"gAlbedoSpec", "gNormal", "gDepth"}) {
    inspector.select(name);
    const uint64_t captures = inspector.captureCount();
    r->render();
    const std::vector<float> copy = inspector.readCaptured();
    EXPECT_EQ(copy, r->readResourceRGBA32F(name)) << name;
    EXPECT_NE(std::count(copy.begin(), copy.end(), 0.0f), std::ptrdiff_t(copy.size())) << name << " is not empty";
    EXPECT_EQ(inspector.captureCount(), captures + 1) << name;
  }
  // gDepth and forwardDepth share a format but not a lifetime step: no new copy texture for frames.
  const uint64_t creations = inspector.textureCreations();
  for (int i = 0; i < 3; ++i) r->render();
  EXPECT_EQ(inspector.textureCreations(), creations);
  inspector.select("gAlbedoSpec");
  r->render();
  EXPECT_EQ(inspector.textureCreations(), creations + 1) << "another format: one new copy texture";
}

// Picking's ids (rg32ui, RendererOptions::picking as rgraph view sets it) are not copied: a float view
// of an integer texture is undefined. The inspector says so.
TEST_F(ViewInspector, ObjectIdsAreNotShownAndSaySo) {
  RendererOptions options;
  options.size = kSize;
  options.picking = true;
  Diagnostics diags;
  auto r = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json", options, diags);
  ASSERT_TRUE(r) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  r->setScene(RenderScene::load("learnopengl:overview"));
  r->render();
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("object_id");
  r->render();
  EXPECT_EQ(inspector.capturedTexture(), 0u);
  EXPECT_EQ(inspector.problem(), "'object_id' holds integer ids (rg32ui): the inspector shows colour and depth only "
                                 "(Renderer::requestPick reads ids)");
}

TEST_F(ViewInspector, OnlyTheAttachedRendererCopiesAndAnUnwrittenNameCopiesNothing) {
  auto first = make(kAliasing), second = make(kAliasing);
  ASSERT_TRUE(first && second);
  ResourceInspector inspector;
  inspector.attach(*first);
  inspector.select("b");
  first->render();
  EXPECT_EQ(inspector.captureCount(), 1u);
  inspector.attach(*second);
  first->render();
  EXPECT_EQ(inspector.captureCount(), 1u) << "the renderer attached before no longer copies";
  second->render();
  EXPECT_EQ(inspector.captureCount(), 2u);
  inspector.select("no_such_resource");
  second->render();
  EXPECT_EQ(inspector.capturedTexture(), 0u);
  EXPECT_EQ(inspector.captureCount(), 2u);
  inspector.detach();
  inspector.select("b");
  second->render();
  EXPECT_EQ(inspector.captureCount(), 2u) << "detached: no hook";
}

// A multisampled target is resolved into the copy (a blit: a copy of the
// samples would not display); a cleared one resolves to its clear colour.
TEST_F(ViewInspector, AMultisampledTargetIsCopiedResolved) {
  auto r = make(R"({
    "version": 1,
    "resources": {
      "ms": { "format": "rgba16f", "samples": 4, "size": "output" },
      "resolved": { "format": "rgba16f", "size": "output" },
      "output": { "format": "rgba8", "size": "output" }
    },
    "passes": [
      { "name": "fill", "type": "clear", "params": { "color": [0.25, 0.5, 0.75, 1.0] }, "outputs": { "color": "ms" } },
      { "name": "resolve", "type": "blit", "inputs": { "src": "ms" }, "outputs": { "dst": "resolved" } },
      { "name": "tonemap", "type": "tonemap", "params": { "operator": "none" },
        "inputs": { "hdr": "resolved" }, "outputs": { "output": "output" } }
    ],
    "output": "output"
  })");
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("ms");
  r->render();
  EXPECT_TRUE(allTexels(inspector.readCaptured(), kFill));
}

// The shipped deferred-ssao-bloom with bloom at full size writing a new HDR
// image (as it shipped before it was made small): bloom's bright-pass image
// then shares its texture with that image, written after it. The copy equals
// what the same passes give when nothing after them runs (the pipeline with
// "bright" as its output), while the texture itself holds something else by
// the end of the frame.
TEST_F(ViewInspector, BloomsAliasedTransientIsCopiedBeforeReuse) {
  const std::string path = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-ssao-bloom.json";
  auto json = nlohmann::ordered_json::parse(std::ifstream(path));
  for (const char* r : {"bright", "blur_a", "blur_b"}) json["resources"][r]["size"] = "output";
  json["resources"]["hdr_bloom"] = {{"format", "rgba16f"}, {"size", "output"}};
  for (auto& pass : json["passes"]) {
    if (pass["name"] != "bloom_composite") continue;
    pass["inputs"] = {{"hdr", "hdr_forward"}, {"bloom", "blur_a"}};
    pass["outputs"] = {{"color", "hdr_bloom"}};
  }
  RendererOptions options;
  options.size = {64, 48};
  Diagnostics diags;
  auto full = Renderer::fromJson(json.dump(), path, options, diags, std::string(RGRAPH_SOURCE_DIR) + "/pipelines");
  ASSERT_TRUE(full) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  json["output"] = "bright";
  auto upToBright =
      Renderer::fromJson(json.dump(), path, options, diags, std::string(RGRAPH_SOURCE_DIR) + "/pipelines");
  ASSERT_TRUE(upToBright) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  auto scene = RenderScene::load("learnopengl:overview");
  full->setScene(scene);
  upToBright->setScene(scene);
  const Plan& plan = full->plan();
  const ResourceIndex bright = findResourceIndex(plan, "bright");
  ASSERT_TRUE(bright.valid());
  ASSERT_GT(plan.physicalTexture(plan.resource(bright).physical).resources.size(), 1u) << "bright is aliased";

  ResourceInspector inspector;
  inspector.attach(*full);
  inspector.select("bright");
  full->render();
  upToBright->render();
  const std::vector<float> expected = upToBright->readResourceRGBA32F("bright");
  EXPECT_EQ(inspector.readCaptured(), expected);
  EXPECT_NE(full->readResourceRGBA32F("bright"), expected) << "its memory was reused later in the frame";
}

// ------------------------------------------------------------ value mapping

TEST(ViewValueMapping, DepthLinearisationInvertsThePerspectiveProjection) {
  Camera camera;
  camera.near = 0.5f;
  camera.far = 40.0f;
  const glm::mat4 proj = camera.projection(1.5f);
  for (float z : {0.5f, 1.0f, 3.0f, 12.5f, 40.0f}) {
    const glm::vec4 clip = proj * glm::vec4(0.0f, 0.0f, -z, 1.0f);
    const float window = clip.z / clip.w * 0.5f + 0.5f;
    EXPECT_NEAR(view::linearizeDepth(window, camera.near, camera.far), z, z * 1e-3f) << z;
  }
  ValueMapping m;
  m.mode = ValueMapping::Mode::depth;
  m.near = 0.5f;
  m.far = 40.0f;
  EXPECT_NEAR(view::mapValue(m, glm::vec4(0.0f)).r, 0.0f, 1e-5f);
  EXPECT_NEAR(view::mapValue(m, glm::vec4(1.0f)).r, 1.0f, 1e-5f);
}

TEST(ViewValueMapping, RemapLogNormalPositionAndChannels) {
  ValueMapping m;
  m.min = 2.0f;
  m.max = 4.0f;
  EXPECT_EQ(view::mapValue(m, glm::vec4(3.0f, 1.0f, 5.0f, 2.0f)), glm::vec4(0.5f, 0.0f, 1.0f, 0.0f));
  m.log = true;
  m.min = 1.0f;
  m.max = 16.0f;
  EXPECT_NEAR(view::mapValue(m, glm::vec4(4.0f)).r, 0.5f, 1e-6f) << "log2 4 is halfway between log2 1 and log2 16";
  m = {};
  m.mode = ValueMapping::Mode::normal;
  EXPECT_EQ(view::mapValue(m, glm::vec4(-1.0f, 0.0f, 1.0f, 1.0f)), glm::vec4(0.0f, 0.5f, 1.0f, 1.0f));
  m.mode = ValueMapping::Mode::position;
  m.boundsMin = glm::vec3(-2.0f, 0.0f, 10.0f);
  m.boundsMax = glm::vec3(2.0f, 4.0f, 20.0f);
  EXPECT_EQ(view::mapValue(m, glm::vec4(0.0f, 1.0f, 20.0f, 1.0f)), glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  m = {};
  m.channel = ValueMapping::Channel::g;
  EXPECT_EQ(view::mapValue(m, glm::vec4(0.1f, 0.6f, 0.2f, 0.3f)), glm::vec4(0.6f, 0.6f, 0.6f, 1.0f));
  m.channel = ValueMapping::Channel::a;
  EXPECT_EQ(view::mapValue(m, glm::vec4(0.1f, 0.6f, 0.2f, 0.3f)), glm::vec4(0.3f, 0.3f, 0.3f, 1.0f));
}

// The display shader mirrors mapValue(): drawn copies equal the CPU mapping of the copied values within 1/255.
TEST_F(ViewInspector, TheDisplayShaderMatchesTheCpuMapping) {
  auto r = viewtest::defaultRenderer({64, 48});
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  struct Case {
    const char* resource;
    ValueMapping mapping;
  };
  ValueMapping depth, normal, position, remap;
  depth.mode = ValueMapping::Mode::depth;
  depth.near = r->camera().near;
  depth.far = r->camera().far;
  normal.mode = ValueMapping::Mode::normal;
  normal.channel = ValueMapping::Channel::b;
  position.mode = ValueMapping::Mode::position;
  position.boundsMin = r->scene()->scene().bounds().min;
  position.boundsMax = r->scene()->scene().bounds().max;
  remap.min = 0.2f;
  remap.max = 0.6f;
  remap.log = true;
  for (const Case& c :
       {Case{"gDepth", depth}, Case{"gNormal", normal}, Case{"gPosition", position}, Case{"gAlbedoSpec", remap}}) {
    inspector.select(c.resource);
    r->render();
    inspector.mapping() = c.mapping;
    const uint32_t display = inspector.renderDisplay();
    ASSERT_NE(display, 0u);
    const Extent e = inspector.capturedExtent();
    std::vector<uint8_t> shown(size_t(e.width) * e.height * 4);
    glGetTextureImage(display, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(shown.size()), shown.data());
    const std::vector<float> values = inspector.readCaptured();  // top-down; `shown` is bottom-up
    size_t off = 0;
    for (uint32_t y = 0; y < e.height; ++y)
      for (uint32_t x = 0; x < e.width; ++x) {
        const float* v = &values[(size_t(e.height - 1 - y) * e.width + x) * 4];
        const glm::vec4 want = view::mapValue(c.mapping, glm::vec4(v[0], v[1], v[2], v[3])) * 255.0f;
        const uint8_t* got = &shown[(size_t(y) * e.width + x) * 4];
        for (int k = 0; k < 4; ++k) off += std::abs(float(got[k]) - want[k]) > 1.01f;
      }
    EXPECT_EQ(off, 0u) << c.resource;
  }
}

}  // namespace
