// The editor's own pass type, registered in-process (RendererOptions::registry),
// and the pipeline that uses it: any pipeline with the pass appended after the
// one that writes its output.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "rgraph/registry.h"

namespace editor {

// The pass type's name in pipelines.
inline constexpr const char* kTintType = "editor_tint";

// rgraph's built-in types (a copy) plus "editor_tint": the image times a
// colour. `shaderFolder` holds editor_tint.frag (named by absolute path, so
// no shader search folder is needed).
rgraph::PassRegistry editorPassTypes(const std::string& shaderFolder);

// `pipelineJson` with an "editor_tint" pass (colour `tint`) between the pass
// that writes the output and the output: that pass writes a new resource of
// the output's format instead. Throws std::runtime_error when the text is not
// JSON or no pass writes the output (the rest is checked by Renderer::fromJson).
std::string withTint(const std::string& pipelineJson, const glm::vec4& tint);

}  // namespace editor
