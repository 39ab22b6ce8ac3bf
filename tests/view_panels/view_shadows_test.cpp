// rgraph view and shadows (issue 28) without a window: the inspector copies
// any layer of the shadow atlas and labels it with what it holds (which light,
// cascade or cube face), the shadows panel lists the budget the shadow_map
// template reported at adapt time, and the bias and filter parameters, edited
// as the parameter panel and the script's `param` edit them, re-expand the
// template and change the frame.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "rgraph/gl/executor.h"
#include "rgraph/renderer.h"
#include "test_support.h"
#include "view_panels.h"
#include "view_test_util.h"

namespace {
using namespace rgraph;
using view::ResourceInspector;

using viewtest::kMapSize;
using viewtest::kShadowPipeline;
using viewtest::kShadowScene;
using viewtest::shadowRenderer;
using viewtest::smallMapsPipeline;

// The layers the budget table gives `light` ("spot0": its row "spot0  128^2  4..4  ..."), as [first, last].
std::optional<std::pair<uint32_t, uint32_t>> tableLayers(const std::vector<std::string>& lines,
                                                         const std::string& light) {
  for (const std::string& l : lines) {
    std::istringstream row(l);
    std::string name, map, layers;
    if (!(row >> name >> map >> layers) || name != light || layers.find("..") == std::string::npos) continue;
    return std::make_pair(uint32_t(std::stoul(layers)), uint32_t(std::stoul(layers.substr(layers.find("..") + 2))));
  }
  return std::nullopt;
}

bool contains(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

// The casting and non-casting lights of a scene under the budget's names ("directional0", "spot1", "point3").
void lightNames(const Scene& scene, std::vector<std::string>& casting, std::vector<std::string>& other) {
  for (size_t i = 0; i < scene.directionalLights.size(); ++i)
    (scene.directionalLights[i].castShadows ? casting : other).push_back("directional" + std::to_string(i));
  for (size_t i = 0; i < scene.pointLights.size(); ++i) {
    const PointLight& l = scene.pointLights[i];
    (l.castsShadows() ? casting : other).push_back((l.spot ? "spot" : "point") + std::to_string(i));
  }
}

// Share of texels of a depth copy (RGBA32F, depth in R) that something was drawn into (depth below 1).
double drawnShare(const std::vector<float>& rgba) {
  size_t drawn = 0;
  for (size_t i = 0; i < rgba.size(); i += 4) drawn += rgba[i] < 1.0f;
  return rgba.empty() ? 0.0 : double(drawn) / double(rgba.size() / 4);
}

class ViewShadows : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

// The shadows panel's text lists every casting light of scenes/shadows.json with its map size and atlas
// layers (4 cascades for the sun, 1 per spot, 6 per point light), the atlas's occupancy and bytes, and
// the lights left without a map with their reason.
TEST_F(ViewShadows, ThePanelListsEveryLightWithItsLayers) {
  auto r = shadowRenderer(smallMapsPipeline());
  ASSERT_TRUE(r);
  r->render();
  const std::vector<std::string> lines = view::shadowPanelLines(*r);
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  SCOPED_TRACE(text);
  EXPECT_EQ(lines.front(), "pass 'shadows':");
  std::vector<std::string> casting, other;
  lightNames(r->scene()->scene(), casting, other);
  ASSERT_EQ(casting.size(), 6u) << "scenes/shadows.json: a sun, two spots, three shadowed point lights";
  ASSERT_EQ(other.size(), 2u);
  uint32_t layers = 0;
  for (const std::string& light : casting) {
    const auto range = tableLayers(lines, light);
    ASSERT_TRUE(range) << light << " has no row";
    const uint32_t want = light.rfind("directional", 0) == 0 ? 4u : light.rfind("spot", 0) == 0 ? 1u : 6u;
    EXPECT_EQ(range->second - range->first + 1, want) << light;
    layers += want;
    EXPECT_TRUE(contains(lines, light)) << light;
  }
  EXPECT_TRUE(contains(lines, std::to_string(kMapSize) + "^2"));
  const uint64_t bytes = uint64_t(kMapSize) * kMapSize * layers * 4;
  EXPECT_TRUE(contains(lines, "atlas: " + std::to_string(layers) + " of " + std::to_string(layers) + " layers used, " +
                                  std::to_string(bytes) + " bytes"));
  for (const std::string& light : other) EXPECT_TRUE(contains(lines, "unshadowed " + light + ": does not cast"));
}

TEST_F(ViewShadows, WithoutShadowMapsThePanelSaysSoAndWhy) {
  // A scene whose lights cast no shadow (learnopengl:overview's 32 point lights: the point-light default).
  auto r = shadowRenderer(smallMapsPipeline(), "learnopengl:overview");
  ASSERT_TRUE(r);
  r->render();
  std::vector<std::string> lines = view::shadowPanelLines(*r);
  EXPECT_EQ(lines.front(), "no shadow maps");
  EXPECT_TRUE(contains(lines, "no casting light reaches the view")) << "the adaptation's note says why";
  // A pipeline without a shadow pass.
  RendererOptions options;
  options.size = {128, 72};
  Diagnostics diags;
  auto plain = Renderer::fromFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr.json", options, diags);
  ASSERT_TRUE(plain);
  plain->setScene(RenderScene::load(kShadowScene));
  lines = view::shadowPanelLines(*plain);
  EXPECT_EQ(lines.front(), "no shadow maps");
}

// Every atlas layer's label names what the budget table says it holds; a point light's cube faces are
// labelled in order, and the labels are right: the face looking down at the floor is drawn all over, the
// one looking up at the empty sky holds (almost) nothing.
TEST_F(ViewShadows, AtlasLayersAreLabelledWithTheirLightAndFace) {
  auto r = shadowRenderer(smallMapsPipeline());
  ASSERT_TRUE(r);
  r->render();
  const std::vector<std::string> lines = view::shadowPanelLines(*r);
  const std::vector<std::string> labels = ResourceInspector::layerLabels(*r, "shadowAtlas");
  std::vector<std::string> casting, other;
  lightNames(r->scene()->scene(), casting, other);
  size_t checked = 0;
  for (const std::string& light : casting) {
    const auto range = tableLayers(lines, light);
    ASSERT_TRUE(range) << light;
    ASSERT_LT(range->second, labels.size());
    for (uint32_t l = range->first; l <= range->second; ++l, ++checked) {
      const uint32_t i = l - range->first;
      const std::string want = light.rfind("directional", 0) == 0 ? light + " cascade " + std::to_string(i)
                               : light.rfind("spot", 0) == 0
                                   ? light
                                   : light + " face " + std::string("+x-x+y-y+z-z").substr(i * 2, 2);
      EXPECT_EQ(labels[l], want) << "layer " << l;
    }
  }
  EXPECT_EQ(checked, labels.size()) << "every layer belongs to a light";

  // The cube faces of point2 (scenes/shadows.json: 1.2 above a floor 40 wide, nothing higher near it).
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("shadowAtlas");
  const auto point = tableLayers(lines, "point2");
  ASSERT_TRUE(point);
  ASSERT_EQ(labels[point->first + 3].substr(labels[point->first + 3].size() - 7), "face -y");
  inspector.setLayer(point->first + 3);
  r->render();
  EXPECT_GT(drawnShare(inspector.readCaptured()), 0.99) << labels[point->first + 3] << ": the floor below";
  inspector.setLayer(point->first + 2);
  r->render();
  EXPECT_LT(drawnShare(inspector.readCaptured()), 0.05) << labels[point->first + 2] << ": the sky above";
}

// The copy of layer L is layer L of the atlas (read here straight from the executor's texture after the
// frame), and different layers hold different maps.
TEST_F(ViewShadows, TheInspectorCopiesTheChosenAtlasLayer) {
  auto r = shadowRenderer(smallMapsPipeline());
  ASSERT_TRUE(r);
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("shadowAtlas");
  r->render();
  const Plan& plan = r->plan();
  const uint32_t layers = uint32_t(ResourceInspector::layerLabels(*r, "shadowAtlas").size());
  ASSERT_GE(layers, 20u);
  for (const PlannedResource& res : plan.resources) {
    if (res.name != "shadowAtlas") continue;
    ASSERT_EQ(plan.physicalTexture(res.physical).resources.size(), 1u) << "the atlas alone in its memory";
  }
  std::vector<std::vector<float>> copies;
  for (uint32_t layer : {0u, 4u, layers - 3}) {
    inspector.setLayer(layer);
    EXPECT_EQ(inspector.layer(), layer);
    r->render();
    ASSERT_EQ(inspector.capturedExtent(), (Extent{kMapSize, kMapSize}));
    std::vector<float> copy = inspector.readCaptured();
    // The atlas's layer read directly (bottom-up rows; the copy's are top-down).
    std::vector<float> depth(size_t(kMapSize) * kMapSize);
    glGetTextureSubImage(r->executor()->textureOf("shadowAtlas"), 0, 0, 0, GLint(layer), kMapSize, kMapSize, 1,
                         GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth.size() * sizeof(float)), depth.data());
    size_t mismatches = 0;
    for (int y = 0; y < kMapSize; ++y)
      for (int x = 0; x < kMapSize; ++x)
        mismatches += copy[(size_t(kMapSize - 1 - y) * kMapSize + x) * 4] != depth[size_t(y) * kMapSize + x];
    EXPECT_EQ(mismatches, 0u) << "layer " << layer;
    EXPECT_GT(drawnShare(copy), 0.01) << "layer " << layer << " has casters drawn";
    copies.push_back(std::move(copy));
  }
  EXPECT_NE(copies[0], copies[1]);
  EXPECT_NE(copies[1], copies[2]);
  EXPECT_NE(copies[0], copies[2]);

  // A layer the atlas lacks copies nothing (and draw() says why).
  inspector.setLayer(layers);
  r->render();
  EXPECT_EQ(inspector.capturedTexture(), 0u);
  EXPECT_EQ(inspector.problem(), "'shadowAtlas' has " + std::to_string(layers) +
                                     " layer(s) and 1 mip level(s): no layer " + std::to_string(layers) +
                                     " at level 0");
  // Depth maps crowd near 1: fitting the range spreads the drawn texels over the display.
  inspector.setLayer(4);
  r->render();
  ASSERT_TRUE(inspector.fitRange());
  const view::ValueMapping& m = inspector.mapping();
  EXPECT_EQ(m.mode, view::ValueMapping::Mode::raw);
  EXPECT_LT(m.min, m.max);
  EXPECT_LT(m.max, 1.0f) << "the cleared texels (1) are left out";
}

// A cube map resource: its six faces are layers labelled +x .. -z, each copied on its own (a clear of
// each face to a different value through the graph's face subresources; side effects: nothing reads them).
TEST_F(ViewShadows, ACubeResourcesFacesAreLabelledAndCopied) {
  std::string passes;
  const char* faces[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (int f = 0; f < 6; ++f)
    passes += std::string(f ? "," : "") + R"({ "name": "face)" + std::to_string(f) +
              R"(", "type": "clear", "side_effect": true, "params": { "color": [)" + std::to_string(0.1 * (f + 1)) +
              R"(, 0, 0, 1] }, "outputs": { "color": "env.face[)" + faces[f] + R"(]" } })";
  const std::string json = R"({ "version": 1,
    "resources": { "env": { "format": "rgba16f", "size": [8, 8], "cube": true },
                   "output": { "format": "rgba8", "size": "output" } },
    "passes": [ )" + passes +
                           R"(,
      { "name": "fill_output", "type": "clear", "outputs": { "color": "output" } } ],
    "output": "output" })";
  RendererOptions options;
  options.size = {8, 8};
  Diagnostics diags;
  auto r = Renderer::fromJson(json, "cube.json", options, diags);
  ASSERT_TRUE(r) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  const std::vector<std::string> labels = ResourceInspector::layerLabels(*r, "env");
  ASSERT_EQ(labels, (std::vector<std::string>{"face +x", "face -x", "face +y", "face -y", "face +z", "face -z"}));
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("env");
  for (uint32_t f = 0; f < 6; ++f) {
    inspector.setLayer(f);
    r->render();
    const std::vector<float> copy = inspector.readCaptured();
    ASSERT_FALSE(copy.empty()) << labels[f];
    EXPECT_NEAR(copy[0], 0.1f * float(f + 1), 1e-3f) << labels[f];
  }
}

// A mip-mapped resource: the level picked is copied at its own size (level 2 of 8x8: 2x2).
TEST_F(ViewShadows, AMipLevelIsCopiedAtItsSize) {
  const std::string json = R"({ "version": 1,
    "resources": { "chain": { "format": "rgba16f", "size": [8, 8], "mips": "full" },
                   "output": { "format": "rgba8", "size": "output" } },
    "passes": [
      { "name": "level0", "type": "clear", "side_effect": true, "params": { "color": [0.25, 0, 0, 1] },
        "outputs": { "color": "chain.mip[0]" } },
      { "name": "level2", "type": "clear", "side_effect": true, "params": { "color": [0.75, 0, 0, 1] },
        "outputs": { "color": "chain.mip[2]" } },
      { "name": "fill_output", "type": "clear", "outputs": { "color": "output" } } ],
    "output": "output" })";
  RendererOptions options;
  options.size = {8, 8};
  Diagnostics diags;
  auto r = Renderer::fromJson(json, "mips.json", options, diags);
  ASSERT_TRUE(r) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  ResourceInspector inspector;
  inspector.attach(*r);
  inspector.select("chain");
  for (uint32_t mip : {0u, 2u}) {
    inspector.setMip(mip);
    r->render();
    EXPECT_EQ(inspector.capturedExtent(), (Extent{8u >> mip, 8u >> mip}));
    const std::vector<float> copy = inspector.readCaptured();
    ASSERT_EQ(copy.size(), size_t(4) * (8 >> mip) * (8 >> mip));
    EXPECT_NEAR(copy[0], mip == 0 ? 0.25f : 0.75f, 1e-3f) << "level " << mip;
  }
  inspector.setMip(4);  // 8x8 has levels 0..3
  r->render();
  EXPECT_EQ(inspector.capturedTexture(), 0u);
  EXPECT_EQ(inspector.problem(), "'chain' has 1 layer(s) and 4 mip level(s): no layer 0 at level 4");
}

// The bias and filter parameters through ParamEditor::withParam (what `param PASS NAME VALUE` and the
// panel's widgets produce) and Renderer::reloadJson: the template is expanded again with the new value
// (its instances carry it) and the frame changes.
TEST_F(ViewShadows, BiasAndFilterEditsChangeTheFrame) {
  // The editor edits a file: the small-maps pipeline written out.
  const std::string path = testing::TempDir() + "view_shadows_pipeline.json";
  std::ofstream(path) << smallMapsPipeline();
  view::ParamEditor editor(path);
  auto r = shadowRenderer(editor.text());
  ASSERT_TRUE(r);
  r->render();
  const std::vector<uint8_t> before = r->readOutputRGBA8();
  struct Edit {
    const char* pass;
    const char* name;
    const char* value;
  };
  for (const Edit& e : {Edit{"shadows", "slope_bias", "40"}, Edit{"shadows", "constant_bias", "4000"},
                        Edit{"shadows", "normal_offset", "12"}, Edit{"lighting", "shadow_filter", "\"hard\""},
                        Edit{"lighting", "pcf_size", "7"}}) {
    SCOPED_TRACE(std::string(e.pass) + " " + e.name + " " + e.value);
    view::ParamEditor fresh(path);  // one edit at a time against the file
    std::string error;
    const std::optional<std::string> text = fresh.withParam(e.pass, e.name, e.value, error);
    ASSERT_TRUE(text) << error;
    Diagnostics diags;
    ASSERT_TRUE(r->reloadJson(*text, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
    r->render();
    const std::vector<uint8_t> after = r->readOutputRGBA8();
    size_t changed = 0;
    for (size_t i = 0; i < after.size(); i += 4)
      changed += std::max({std::abs(after[i] - before[i]), std::abs(after[i + 1] - before[i + 1]),
                           std::abs(after[i + 2] - before[i + 2])}) > 2;
    std::cout << e.pass << " " << e.name << " " << e.value << ": " << changed << " of " << after.size() / 4
              << " pixels changed by more than 2/255\n";
    EXPECT_GT(changed, after.size() / 4 / 200) << "at least 0.5% of the frame";
    if (std::string(e.pass) == "shadows") {  // every instance of the template carries the edited value
      const PipelineConfig& p = r->pipeline();
      size_t instances = 0;
      for (size_t i = 0; i < p.graph.passes.size(); ++i) {
        if (p.graph.passes[i].type != "shadow_map") continue;
        ++instances;
        EXPECT_EQ(p.params[i].getNumber(e.name), std::stod(e.value)) << p.graph.passes[i].name;
      }
      EXPECT_GE(instances, 10u);
    }
  }
}

}  // namespace
