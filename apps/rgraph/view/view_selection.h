// The object a click (or a script's `pick X Y`) selected in rgraph view:
// the lines the Selection panel shows and the viewer prints, from the
// renderer's answer (Renderer::pickResult) and the scene's object data.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rgraph/renderer.h"

namespace rgraph::view {

// "picked (X, Y) in frame F: instance N 'name', triangle T", then the
// material ("material M 'name': base colour R G B A, metallic M, roughness
// R, emissive R G B") and the transform ("translation X Y Z", the matrix's
// rows); "picked (X, Y) in frame F: nothing" for the background; the
// problem when there is no answer. GL-free.
std::vector<std::string> describePick(const RenderScene& scene, const PickResult& pick);

// The Selection window (ImGui): describePick's lines, or a hint to click.
void drawSelection(const RenderScene* scene, const std::optional<PickResult>& selected);

}  // namespace rgraph::view
