// Shipped pipelines on the other scenes (issue 31): every pipeline on each
// procedural scene under every mode over 2 frames (scene adaptation gives
// each scene its own plan: what aliasing, order and culling act on), and the
// pipelines that draw the scene in every shipped way on each shared glTF
// sample (../shared/assets/gltf; a missing sample fails its test, naming the
// file) under poison and state-scramble, the two modes whose outcome depends
// on what the scene makes the passes do (which materials, textures, skins,
// lights and shadow casters they draw), over one frame. 32x32; each test
// takes one scene and a part of its pipelines. Each run's compared pixels are
// printed (docs/testing.md's table).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hazards/shipped_pipelines.h"
#include "rgraph/hazard_check.h"
#include "test_support.h"

namespace {

using namespace rgraph;

// On the glTF samples, the pipelines whose passes draw the scene in every
// way the shipped ones do: G-buffers in the classic (default), pbr
// (deferred-pbr-shadows, with shadow maps of the sample's casters) and
// compact layouts, forward shading of blended surfaces (every pipeline's
// `forward` pass) and forward_lit (forward-plus).
const std::vector<std::string> kGltfPipelines = {"default", "deferred-pbr-shadows", "deferred-compact",
                                                 "forward-plus"};

// The pipeline's file; a shadow-mapping one as a copy with 256^2 maps instead
// of 2048^2 (in the test's temporary folder): what its passes rely on does not
// change with the map size, and reading four 2048^2 layers back after every
// pass takes seconds a run.
std::string pipelineFile(const std::string& name) {
  const std::string shipped = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/" + name + ".json";
  std::ifstream in(shipped);
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string big = "\"size\": 2048";
  const size_t at = json.find(big);
  if (at == std::string::npos) return shipped;
  json.replace(at, big.size(), "\"size\": 256");
  const std::filesystem::path copy = std::filesystem::temp_directory_path() /
                                     ("rgraph-hazard-" + std::to_string(::getpid()) + "-" + name + ".json");
  std::ofstream(copy) << json;
  return copy.string();
}

struct SceneCase {
  std::string scene;  // RenderScene::load's spec
  std::vector<std::string> pipelines;
  size_t part = 0;  // of the scene's pipelines, in parts small enough for a sanitizer build
  bool everyMode = false;  // every mode over 2 frames, else poison and state-scramble over 1
};

// The scene's pipelines in parts of `per`: each test stays under ~10 s in
// the ASan+UBSan Debug build (the whole scene in one test took up to 17 s there).
void addParts(std::vector<SceneCase>& out, const std::string& scene, const std::vector<std::string>& pipelines,
              size_t per, bool everyMode) {
  for (size_t first = 0, part = 1; first < pipelines.size(); first += per, ++part)
    out.push_back({scene,
                   std::vector<std::string>(pipelines.begin() + static_cast<std::ptrdiff_t>(first),
                                            pipelines.begin() + static_cast<std::ptrdiff_t>(
                                                                    std::min(first + per, pipelines.size()))),
                   part, everyMode});
}

std::vector<SceneCase> cases() {
  std::vector<SceneCase> c;
  for (const char* scene : {"learnopengl", "learnopengl:shadows", "many-lights:64", "thin", "walker"})
    addParts(c, scene, hazardtest::shippedPipelines(), 2, true);
  for (const char* model :
       {"AlphaBlendModeTest/AlphaBlendModeTest.glb", "AnimatedCube/AnimatedCube.gltf", "Box/Box.glb",
        "BoxTextured/BoxTextured.glb", "Cube/Cube.gltf", "DamagedHelmet/DamagedHelmet.glb",
        "EmissiveStrengthTest/EmissiveStrengthTest.glb", "LightsPunctualLamp/LightsPunctualLamp.gltf",
        "MeshPrimitiveModes/MeshPrimitiveModes.gltf", "MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb",
        "MorphPrimitivesTest/MorphPrimitivesTest.glb", "NormalTangentMirrorTest/NormalTangentMirrorTest.glb",
        "RecursiveSkeletons/RecursiveSkeletons.glb", "SimpleInstancing/SimpleInstancing.glb",
        "SimpleMorph/SimpleMorph.gltf", "SimpleSkin/SimpleSkin.gltf", "SpecularTest/SpecularTest.glb",
        "Suzanne/Suzanne.gltf", "TextureCoordinateTest/TextureCoordinateTest.glb",
        "TextureLinearInterpolationTest/TextureLinearInterpolationTest.glb",
        "TextureSettingsTest/TextureSettingsTest.glb", "TextureTransformTest/TextureTransformTest.gltf",
        "UnlitTest/UnlitTest.glb", "VertexColorTest/VertexColorTest.glb"})
    addParts(c, std::string(RGRAPH_ASSETS_DIR) + "/gltf/" + model, kGltfPipelines, 2, false);
  return c;
}

class HazardScenes : public ::testing::TestWithParam<SceneCase> {};

TEST_P(HazardScenes, NoFinding) {
  testsupport::sharedGlContext();
  const SceneCase& c = GetParam();
  HazardCheckOptions o;
  o.scene = c.scene;
  o.size = {32, 32};
  o.frames = c.everyMode ? 2 : 1;
  if (!c.everyMode) o.modes = HazardModes{}.add(HazardMode::poison).add(HazardMode::stateScramble);
  o.renderer.runChecks = false;  // validate's own tests check them; here only what runs
  for (const std::string& name : c.pipelines) {
    const std::string file = pipelineFile(name);
    const HazardReport r = checkHazards(file, o);
    if (file.find("rgraph-hazard-") != std::string::npos) std::filesystem::remove(file);
    ASSERT_TRUE(r.error.empty()) << name << ": " << r.error;
    EXPECT_TRUE(r.hazardFree()) << r.describe();
    ASSERT_EQ(r.runs.size(), c.everyMode ? 8u : 2u) << name;
    for (const HazardModeRun& run : r.runs) {
      EXPECT_GT(run.comparedPixels, 0u) << name << " " << run.mode;
      std::printf("[ hazards  ] %s %s %s %zu\n", name.c_str(), run.mode.c_str(), c.scene.c_str(),
                  run.comparedPixels);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, HazardScenes, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<SceneCase>& i) {
                           // glTF samples' tests start "gltf_".
                           const bool gltf = i.param.scene.find('/') != std::string::npos;
                           const std::string file = i.param.scene.substr(i.param.scene.rfind('/') + 1);
                           return hazardtest::testName((gltf ? "gltf_" : "") + file.substr(0, file.find('.')) +
                                                       "_part" + std::to_string(i.param.part));
                         });

}  // namespace
