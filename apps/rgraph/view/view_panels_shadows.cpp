// The shadows panel: the shadow budget a shadow_map template reported when
// the pipeline was adapted to the scene (Renderer::adaptTables, the same
// lines `rgraph plan --scene` prints), and the adaptation's notes, which say
// why a light or the whole pipeline went without maps.
#include <imgui.h>

#include "view_panels.h"

namespace rgraph::view {

std::vector<std::string> shadowPanelLines(const Renderer& renderer) {
  std::vector<std::string> lines;
  // Only shadow_map templates report tables today (AdaptReport::tables); a
  // pass type that reports another table shows here too, under its pass.
  for (const AdaptReport::Table& t : renderer.adaptTables()) {
    lines.push_back("pass '" + t.pass + "':");
    for (const std::string& l : t.lines) lines.push_back("  " + l);
  }
  if (lines.empty()) lines.push_back(renderer.scene() ? "no shadow maps" : "no shadow maps (no scene)");
  if (!renderer.adaptNotes().empty()) lines.push_back("scene adaptation:");
  for (const std::string& n : renderer.adaptNotes()) lines.push_back("  " + n);
  return lines;
}

void drawShadowsPanel(const Renderer& renderer) {
  const std::vector<std::string> lines = shadowPanelLines(renderer);
  // The table's columns are aligned with spaces: the default font is monospaced. No wrapping, a scroll bar.
  ImGui::BeginChild("shadow budget", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
  for (const std::string& l : lines) {
    const bool heading = !l.empty() && l[0] != ' ';
    if (heading)
      ImGui::TextColored(ImVec4(0.6f, 0.8f, 1.0f, 1.0f), "%s", l.c_str());
    else
      ImGui::TextUnformatted(l.c_str());
  }
  ImGui::EndChild();
}

}  // namespace rgraph::view
