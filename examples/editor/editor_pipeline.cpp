#include "editor_pipeline.h"

#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"

namespace editor {
namespace {

// The pass: a full-screen triangle (rgraph/gl/fullscreen.h) with the colour
// as a uniform, set from the pipeline's "color" parameter every frame.
class TintPass final : public rgraph::gl::FullscreenPass {
  void update(rgraph::PassContext& ctx) override {
    const std::vector<double> c = ctx.params().getVector("color");
    color_.set(float(c[0]), float(c[1]), float(c[2]), float(c[3]));
  }
  ProgramUniform color_{this, "u_color"};  // looked up once, at setup
};

}  // namespace

rgraph::PassRegistry editorPassTypes(const std::string& shaderFolder) {
  using namespace rgraph::decl;
  rgraph::PassTypeDesc tint = passType(kTintType, "the editor's look: the image times a colour");
  tint.slots = {slot("src", rgraph::Access::sampled, true, rgraph::SlotDecl::Load::never, "the frame"),
                slot("dst", rgraph::Access::color_attachment, true, rgraph::SlotDecl::Load::never, "the result")};
  tint.params = {ranged("color", rgraph::ParamType::vec4, std::vector<double>{1, 1, 1, 1}, 0.0, 1.0, "factor")};
  tint.programs = rgraph::gl::fullscreenPrograms(shaderFolder + "/editor_tint.frag", {{"src", "u_src", 0}});
  tint.create = [] { return std::make_unique<TintPass>(); };

  rgraph::PassRegistry types = rgraph::PassRegistry::builtins();  // a copy: ours stay ours
  std::string error;
  if (!types.add(std::move(tint), &error)) throw std::runtime_error("cannot register " + std::string(kTintType) + ": " + error);
  return types;
}

std::string withTint(const std::string& pipelineJson, const glm::vec4& tint) {
  // ordered_json keeps the file's order, so diagnostics read like the file.
  nlohmann::ordered_json p = nlohmann::ordered_json::parse(pipelineJson, nullptr, false);
  if (p.is_discarded() || !p.is_object() || !p.contains("output") || !p["output"].is_string())
    throw std::runtime_error("the pipeline is not JSON with an \"output\" resource");
  const std::string output = p["output"];
  const std::string untinted = "editor_untinted";
  bool found = false;
  for (auto& pass : p["passes"]) {
    if (!pass.contains("outputs")) continue;
    for (auto& [slot, resource] : pass["outputs"].items())
      if (resource == output) resource = untinted, found = true;
  }
  if (!found) throw std::runtime_error("no pass of the pipeline writes its output '" + output + "'");
  // The new resource is declared like the output (its format and size), but rgraph's own.
  nlohmann::ordered_json decl = p["resources"][output];
  decl.erase("imported");
  p["resources"][untinted] = decl;
  p["passes"].push_back({{"name", "editor_tint"},
                         {"type", kTintType},
                         {"params", {{"color", {tint.r, tint.g, tint.b, tint.a}}}},
                         {"inputs", {{"src", untinted}}},
                         {"outputs", {{"dst", output}}}});
  return p.dump(2);
}

}  // namespace editor
