// The plan panel: what the render graph made of the pipeline this frame.
#include "view_panels.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace rgraph::view {

namespace {

// One colour per physical texture, so that resources sharing memory
// (aliased) show the same colour.
ImVec4 physicalColour(uint32_t index) {
  float r, g, b;
  ImGui::ColorConvertHSVtoRGB(float(index) * 0.61803f - float(int(float(index) * 0.61803f)), 0.55f, 0.9f, r, g, b);
  return ImVec4(r, g, b, 1.0f);
}

std::string megabytes(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
  return buf;
}

void drawPasses(Renderer& renderer, const Plan& plan) {
  const std::vector<Renderer::PassTiming> timings = renderer.timings();
  if (renderer.cpuTimed()) {
    // Software renderer: pass times need a glFinish after each pass, which
    // stalls the frame; "profile" turns that on.
    bool profile = renderer.cpuPassTiming();
    if (ImGui::Checkbox("profile", &profile)) renderer.setCpuPassTiming(profile);
    ImGui::SameLine();
  }
  ImGui::TextDisabled("%s", !renderer.cpuTimed() ? "time: GPU timer queries (GL_TIME_ELAPSED)"
                            : renderer.cpuPassTiming() ? "time: CPU time, glFinish after each pass"
                                                       : "time: off (profile to time each pass)");
  if (!renderer.cpuTimed()) {
    // Query results come in frames later (render() never waits for them): say which frame the column is.
    const std::optional<uint64_t> frame = renderer.timingsFrame();
    if (frame)
      ImGui::TextDisabled("of frame %llu (%llu behind)", static_cast<unsigned long long>(*frame),
                          static_cast<unsigned long long>(renderer.frameIndex() - 1 - *frame));
    else
      ImGui::TextDisabled("no frame's times in yet");
  }
  if (!ImGui::BeginTable("passes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) return;
  ImGui::TableSetupColumn("step");
  ImGui::TableSetupColumn("pass");
  ImGui::TableSetupColumn("type");
  ImGui::TableSetupColumn("ms");
  ImGui::TableHeadersRow();
  double total = 0.0;
  for (size_t s = 0; s < plan.order.size(); ++s) {
    const PlannedPass& p = plan.pass(plan.order[s]);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%zu", s);
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(p.name.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(p.type.c_str());
    ImGui::TableNextColumn();
    // timings() lists executed passes in execution order; match by name in case it lags a reload.
    if (s < timings.size() && timings[s].name == p.name) {
      ImGui::Text("%.3f", timings[s].ms);
      total += timings[s].ms;
    }
  }
  for (const PlannedPass& p : plan.passes) {
    if (!p.culled) continue;
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextDisabled("-");
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%s", p.name.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("culled: %s", p.reason.c_str());
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%s", p.type.c_str());
    ImGui::TableNextColumn();
    ImGui::TextDisabled("culled: %s", p.reason.c_str());
  }
  ImGui::EndTable();
  ImGui::Text("total %.3f ms", total);
}

// One row per resource: a bar over the steps it lives, coloured by its
// physical texture.
void drawLifetimes(const Plan& plan) {
  const size_t steps = std::max<size_t>(plan.order.size(), 1);
  if (!ImGui::BeginTable("resources", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) return;
  ImGui::TableSetupColumn("resource");
  ImGui::TableSetupColumn("memory");
  ImGui::TableSetupColumn("lifetime (steps)", ImGuiTableColumnFlags_WidthStretch, 3.0f);
  ImGui::TableHeadersRow();
  for (const PlannedResource& r : plan.resources) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const bool used = r.firstPass.valid();
    if (used)
      ImGui::TextUnformatted(r.name.c_str());
    else
      ImGui::TextDisabled("%s", r.name.c_str());
    if (ImGui::IsItemHovered() && r.versions.size() > 1) {
      std::string versions;
      for (const std::string& v : r.versions) versions += (versions.empty() ? "" : " -> ") + v;
      ImGui::SetTooltip("versions: %s", versions.c_str());
    }
    ImGui::TableNextColumn();
    ImVec4 colour(0.6f, 0.6f, 0.6f, 1.0f);
    if (r.imported)
      ImGui::TextUnformatted("imported");
    else if (r.physical.valid()) {
      colour = physicalColour(r.physical.value());
      const PhysicalTexture& ph = plan.physicalTexture(r.physical);
      ImGui::TextColored(colour, "phys #%u%s", r.physical.value(), ph.resources.size() > 1 ? " (shared)" : "");
    } else
      ImGui::TextDisabled("unused");
    ImGui::TableNextColumn();
    if (!used) continue;
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x, height = ImGui::GetTextLineHeight();
    const float x0 = origin.x + width * float(r.firstPass.value()) / float(steps);
    const float x1 = origin.x + width * float(r.lastPass.value() + 1) / float(steps);
    ImGui::GetWindowDrawList()->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1, origin.y + height),
                                              ImGui::ColorConvertFloat4ToU32(colour), 2.0f);
    ImGui::Dummy(ImVec2(width, height));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s: steps %u-%u, %s", r.name.c_str(), r.firstPass.value(), r.lastPass.value(),
                        megabytes(r.bytes).c_str());
  }
  ImGui::EndTable();
}

}  // namespace

void drawPlanPanel(Renderer& renderer) {
  const Plan& plan = renderer.plan();
  ImGui::Text("%ux%u, %zu passes run, %zu culled", plan.output.width, plan.output.height, plan.order.size(),
              plan.passes.size() - plan.order.size());
  ImGui::Text("transient memory: %s allocated, %s without aliasing (%zu physical textures)",
              megabytes(plan.allocatedBytes).c_str(), megabytes(plan.naiveBytes).c_str(), plan.physical.size());
  if (ImGui::CollapsingHeader("Passes", ImGuiTreeNodeFlags_DefaultOpen)) drawPasses(renderer, plan);
  if (ImGui::CollapsingHeader("Resources", ImGuiTreeNodeFlags_DefaultOpen)) drawLifetimes(plan);
}

std::optional<std::string> drawPanels(Renderer& renderer, ParamEditor& editor, ResourceInspector& inspector,
                                      std::string* showTab) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  constexpr float kMargin = 10.0f, kCameraWindow = 120.0f;  // view_main.cpp's camera window, lower left
  const float side = std::clamp(display.x * 0.4f, 280.0f, 620.0f);
  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(side, std::max(display.y - 2 * kMargin - kCameraWindow, 160.0f)),
                           ImGuiCond_FirstUseEver);
  std::optional<std::string> edit;
  auto tab = [&](const char* label, const char* name) {
    const bool show = showTab && *showTab == name;
    if (show) showTab->clear();
    return ImGui::BeginTabItem(label, nullptr, show ? ImGuiTabItemFlags_SetSelected : 0);
  };
  if (ImGui::Begin("rgraph") && ImGui::BeginTabBar("panels")) {
    if (tab("Plan", "plan")) {
      drawPlanPanel(renderer);
      ImGui::EndTabItem();
    }
    if (tab("Parameters", "parameters")) {
      edit = editor.draw(renderer);
      ImGui::EndTabItem();
    }
    if (tab("Shadows", "shadows")) {
      drawShadowsPanel(renderer);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(display.x - kMargin, kMargin), ImGuiCond_FirstUseEver, ImVec2(1, 0));
  ImGui::SetNextWindowSize(ImVec2(side, std::max(display.y * 0.75f, 160.0f)), ImGuiCond_FirstUseEver);
  // Folded until opened, unless something is already picked (a script's `inspect`): an empty window's area
  // is fill time on a software renderer.
  ImGui::SetNextWindowCollapsed(inspector.selected().empty(), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Inspector")) inspector.draw(renderer);
  ImGui::End();
  return edit;
}

}  // namespace rgraph::view
