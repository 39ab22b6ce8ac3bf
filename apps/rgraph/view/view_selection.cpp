#include "view_selection.h"

#include <imgui.h>

#include <cstdio>

namespace rgraph::view {

namespace {
std::string numbers(const float* v, int n) {
  std::string s;
  char buf[32];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "%s%.4g", i ? " " : "", double(v[i]));
    s += buf;
  }
  return s;
}
}  // namespace

std::vector<std::string> describePick(const RenderScene& scene, const PickResult& pick) {
  const std::string where = "picked (" + std::to_string(pick.x) + ", " + std::to_string(pick.y) + ")";
  if (!pick.problem.empty()) return {where + ": no answer: " + pick.problem};
  const std::string frame = " in frame " + std::to_string(pick.frame);
  if (!pick.instance || !scene.contains(pick.instance)) return {where + frame + ": nothing"};
  const Scene& s = scene.scene();
  const Primitive& p = s.primitives[scene.primitiveIndex(pick.instance)];
  std::vector<std::string> lines = {where + frame + ": instance " + std::to_string(pick.instance.value) + " '" +
                                    p.name + "', triangle " + std::to_string(pick.triangle)};
  if (p.material >= 0 && size_t(p.material) < s.materials.size()) {
    const Material& m = s.materials[size_t(p.material)];
    lines.push_back("material " + std::to_string(p.material) + " '" + m.name + "': base colour " +
                    numbers(&m.baseColorFactor.x, 4) + ", metallic " + numbers(&m.metallicFactor, 1) +
                    ", roughness " + numbers(&m.roughnessFactor, 1) + ", emissive " +
                    numbers(&m.emissiveFactor.x, 3));
  } else {
    lines.push_back("material: the default");
  }
  const glm::mat4& t = scene.transform(pick.instance);
  lines.push_back("translation " + numbers(&t[3].x, 3));
  for (int row = 0; row < 4; ++row) {
    const float r[4] = {t[0][row], t[1][row], t[2][row], t[3][row]};
    lines.push_back("transform row " + std::to_string(row) + ": " + numbers(r, 4));
  }
  return lines;
}

void drawSelection(const RenderScene* scene, const std::optional<PickResult>& selected) {
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 10, ImGui::GetIO().DisplaySize.y - 10),
                          ImGuiCond_FirstUseEver, ImVec2(1, 1));
  ImGui::Begin("Selection");
  if (!selected || !scene)
    ImGui::TextDisabled("click an object to select it");
  else
    for (const std::string& line : describePick(*scene, *selected)) ImGui::TextUnformatted(line.c_str());
  ImGui::End();
}

}  // namespace rgraph::view
