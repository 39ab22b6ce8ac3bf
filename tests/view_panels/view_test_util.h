// Shared by the view panel tests: the default pipeline with the LearnOpenGL
// scene, as the viewer opens it, at a small size; a small pipeline whose
// transients alias and whose content is known.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "renderer_util.h"
#include "rgraph/renderer.h"

namespace rgraph::viewtest {

inline const std::string kDefaultPipeline = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";

// "a" is filled with kFill and dies after its copy into "b"; "c" takes a's
// memory (same format and size, later lifetime) and ends as c + (1 - b).
// fill_unused feeds nothing: culled.
inline const char* kAliasing = R"({
  "version": 1,
  "resources": {
    "a": { "format": "rgba16f", "size": "output" },
    "b": { "format": "rgba16f", "size": "output" },
    "c": { "format": "rgba16f", "size": "output" },
    "output": { "format": "rgba8", "size": "output" },
    "unused": { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "fill_a", "type": "clear", "params": { "color": [0.25, 0.5, 0.75, 1.0] }, "outputs": { "color": "a" } },
    { "name": "copy_b", "type": "blit", "inputs": { "src": "a" }, "outputs": { "dst": "b" } },
    { "name": "fill_c", "type": "clear", "params": { "color": [0.125, 0.0, 0.0, 1.0] }, "outputs": { "color": "c" } },
    { "name": "add_b", "type": "fullscreen", "params": { "shader": "invert.frag", "blend": "additive" },
      "inputs": { "input0": "b", "color": "c" }, "outputs": { "color": "c_2" } },
    { "name": "tonemap", "type": "tonemap", "params": { "operator": "none" },
      "inputs": { "hdr": "c_2" }, "outputs": { "output": "output" } },
    { "name": "fill_unused", "type": "clear", "outputs": { "color": "unused" } }
  ],
  "output": "output"
})";

// nullptr (and a test failure naming the first diagnostic) when it cannot be made.
inline std::unique_ptr<Renderer> defaultRenderer(Extent size) {
  RendererOptions options;
  options.size = size;
  return testsupport::makeRenderer(kDefaultPipeline, options, RenderScene::load("learnopengl:overview"));
}

// The shipped shadow pipeline (issue 28) with small maps, as the parameter editor would write it, and a
// renderer of it on the shadows scene at a small size.
inline const std::string kShadowPipeline = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr-shadows.json";
inline const std::string kShadowScene = std::string(RGRAPH_SOURCE_DIR) + "/scenes/shadows.json";
constexpr int kMapSize = 128;  // texels per side of each map: small, for llvmpipe

inline std::string smallMapsPipeline() {
  std::ifstream in(kShadowPipeline);
  auto json = nlohmann::ordered_json::parse(in);
  for (auto& pass : json["passes"])
    if (pass["name"] == "shadows") pass["params"]["size"] = kMapSize;
  return json.dump(2);
}

inline std::unique_ptr<Renderer> shadowRenderer(const std::string& json, const std::string& scene = kShadowScene,
                                                Extent size = {128, 72}) {
  RendererOptions options;
  options.size = size;
  return testsupport::makeRenderer(json, options, RenderScene::load(scene), kShadowPipeline);
}

}  // namespace rgraph::viewtest
