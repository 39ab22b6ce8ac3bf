// Shared by the public-API renderer tests (renderer/, view_panels/): a
// pipeline of the geometry pass alone with one more output asked for, and a
// renderer made of either a pipeline file or JSON text, throwing its first
// diagnostic. Their scenes: cube_scene.h.
#pragma once

#include <memory>
#include <string>

#include "cube_scene.h"
#include "rgraph/renderer.h"

namespace rgraph::testsupport {

// A pipeline of default.json's G-buffer pass alone (its output: the albedo),
// with the geometry pass's optional output `output` ("velocity",
// "object_id") turned on by its parameter of the same name and written to a
// resource `resource` of `format`. `jitter` > 0 jitters the camera over that
// many frames; `positionFormat` is the position target's format.
struct GBufferExtra {
  std::string output;
  std::string resource;
  std::string format;
  int jitter = 0;
  std::string positionFormat = "rgba16f";
};
std::string gbufferPipeline(const GBufferExtra& extra);

// A renderer of `pipeline` (JSON text when it starts with '{' after white
// space, named `name` in diagnostics; otherwise a file's path) drawing
// `scene`; std::runtime_error naming the first diagnostic when it cannot be
// made (gtest fails the test with it).
std::unique_ptr<Renderer> makeRenderer(const std::string& pipeline, const RendererOptions& options,
                                       std::shared_ptr<RenderScene> scene, const std::string& name = "pipeline.json");

}  // namespace rgraph::testsupport
