// validate, plan, dot: everything that needs no GL context (and cmd_passes.cpp).
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "rgraph/adapt.h"
#include "rgraph/error.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/shader_check.h"

namespace rgraph::cli {
namespace {

// Loads, compiles and checks (checkPipeline); prints nothing. Returns nullopt
// only when the config itself could not be built.
std::optional<std::pair<PipelineConfig, Plan>> loadAndCompile(const std::string& path, const SizeOptions& size,
                                                              Diagnostics& diags,
                                                              ShaderChecks shaders = ShaderChecks::skip) {
  auto pipeline = loadPipeline(path, diags);
  if (!pipeline) return std::nullopt;
  Plan plan = checkPipeline(*pipeline, compileOptions(size.width, size.height, size.maxTextureSize), shaders, diags);
  return std::make_pair(std::move(*pipeline), std::move(plan));
}

// The plans printed here are ok (rgraph/graph.h: valid steps name passes that run).
template <class Tag>
nlohmann::json indexJson(PlanIndex<Tag> i) {
  return i.valid() ? nlohmann::json(i.value()) : nlohmann::json(nullptr);
}

nlohmann::json passName(const Plan& plan, StepIndex step) {
  return step.valid() ? nlohmann::json(plan.pass(plan.step(step)).name) : nlohmann::json(nullptr);
}

nlohmann::json planJson(const Plan& plan) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : plan.passes) {
    passes.push_back({{"name", p.name},
                      {"type", p.type},
                      {"order", indexJson(p.order)},
                      {"culled", p.culled},
                      {"reason", p.reason}});
  }
  nlohmann::json resources = nlohmann::json::array();
  for (const auto& r : plan.resources) {
    resources.push_back({{"name", r.name},
                         {"kind", r.kind == ResourceKind::texture ? "texture" : "buffer"},
                         {"imported", r.imported},
                         {"width", r.extent.width},
                         {"height", r.extent.height},
                         {"first_pass", passName(plan, r.firstPass)},
                         {"last_pass", passName(plan, r.lastPass)},
                         {"first_order", indexJson(r.firstPass)},
                         {"last_order", indexJson(r.lastPass)},
                         {"physical", indexJson(r.physical)},
                         {"bytes", r.bytes},
                         {"versions", r.versions},
                         {"history_of", r.historyOf.valid() ? nlohmann::json(plan.resource(r.historyOf).name)
                                                            : nlohmann::json(nullptr)},
                         {"kept_across_frames", r.historyOf.valid() || r.history.valid()}});
  }
  nlohmann::json physical = nlohmann::json::array();
  for (const auto& ph : plan.physical) {
    nlohmann::json names = nlohmann::json::array();
    for (ResourceIndex r : ph.resources) names.push_back(plan.resource(r).name);
    physical.push_back({{"format", formatName(ph.format)},
                        {"width", ph.extent.width},
                        {"height", ph.extent.height},
                        {"bytes", ph.bytes},
                        {"resources", names}});
  }
  return {{"output", {{"width", plan.output.width}, {"height", plan.output.height}}},
          {"passes", passes},
          {"resources", resources},
          {"physical", physical},
          {"memory", memoryJson(plan)}};
}

std::string mib(uint64_t bytes) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB";
  return s.str();
}

void printPlanText(const Plan& plan) {
  std::cout << "passes (" << plan.order.size() << " run, " << plan.passes.size() - plan.order.size()
            << " culled) at " << plan.output.width << "x" << plan.output.height << ":\n";
  for (PassIndex idx : plan.order) {
    const auto& p = plan.pass(idx);
    std::cout << "  " << std::setw(3) << p.order.value() << "  " << std::left << std::setw(24) << p.name << std::right
              << " (" << p.type << ")";
    if (!p.reason.empty()) std::cout << "  " << p.reason;  // kept only for the next frame
    std::cout << "\n";
  }
  for (const auto& p : plan.passes)
    if (p.culled) std::cout << "  cut  " << std::left << std::setw(24) << p.name << std::right << " " << p.reason << "\n";
  std::cout << "resources:\n";
  for (const auto& r : plan.resources) {
    std::cout << "  " << std::left << std::setw(20) << r.name << std::right;
    if (!r.firstPass.valid()) {
      std::cout << " unused\n";
      continue;
    }
    std::cout << " passes " << r.firstPass.value() << ".." << r.lastPass.value();
    if (r.imported)
      std::cout << "  imported";
    else
      std::cout << "  physical #" << r.physical.value();
    std::cout << "  " << mib(r.bytes);
    if (r.historyOf.valid())
      std::cout << "  history of " << plan.resource(r.historyOf).name << ", kept across frames";
    else if (r.history.valid())
      std::cout << "  kept across frames (history: " << plan.resource(r.history).name << ")";
    std::cout << "\n";
  }
  std::cout << "memory: naive " << mib(plan.naiveBytes) << ", allocated " << mib(plan.allocatedBytes) << " in "
            << plan.physical.size() << " physical textures; peak live " << mib(plan.peakLiveBytes)
            << " (the least any allocator needs)\n";
}

std::string lightLabel(const SceneFeatures::ShadowLight& l) {
  using Kind = SceneFeatures::ShadowLight::Kind;
  const char* kind = l.kind == Kind::directional ? "directional" : l.kind == Kind::spot ? "spot" : "point";
  return std::string(kind) + " " + std::to_string(l.light);
}

// Which lights a shadow pipeline gives maps (most important first) and why
// each other light gets none (scene order). Indices are into the scene's
// directional lights or its point lights (spots included), as in shadow pass names.
void printShadows(const SceneFeatures& f) {
  std::cout << "shadows:" << (f.shadowCasters ? "" : " (no caster in the scene)") << "\n";
  if (f.shadowLights.empty() && f.unshadowedLights.empty()) std::cout << "  (no lights)\n";
  for (const auto& l : f.shadowLights) std::cout << "  shadowed: " << lightLabel(l) << "\n";
  for (const auto& u : f.unshadowedLights)
    std::cout << "  unshadowed: " << lightLabel(u.light) << " (" << u.reason << ")\n";
}

nlohmann::json reportsJson(const AdaptReport& report) {
  nlohmann::json out = nlohmann::json::array();
  for (const AdaptReport::Table& t : report.tables) out.push_back({{"pass", t.pass}, {"lines", t.lines}});
  return out;
}

nlohmann::json shadowsJson(const SceneFeatures& f) {
  auto light = [](const SceneFeatures::ShadowLight& l) {
    const std::string label = lightLabel(l);
    return nlohmann::json{{"kind", label.substr(0, label.find(' '))}, {"light", l.light}};
  };
  nlohmann::json shadowed = nlohmann::json::array(), unshadowed = nlohmann::json::array();
  for (const auto& l : f.shadowLights) shadowed.push_back(light(l));
  for (const auto& u : f.unshadowedLights) {
    nlohmann::json j = light(u.light);
    j["reason"] = u.reason;
    unshadowed.push_back(std::move(j));
  }
  return {{"casters", f.shadowCasters}, {"shadowed", shadowed}, {"unshadowed", unshadowed}};
}

}  // namespace

int runValidate(const std::string& path, const SizeOptions& size, bool json, bool checkShaders) {
  Diagnostics diags;
  loadAndCompile(path, size, diags, checkShaders ? ShaderChecks::run : ShaderChecks::skip);
  if (json)
    std::cout << diagnosticsJson(diags) << "\n";
  else
    printDiagnostics(diags);
  if (hasErrors(diags)) return kExitFailure;
  if (!json) std::cout << path << ": valid\n";
  return kExitOk;
}

int runPlan(const std::string& path, const SizeOptions& size, bool json, const std::string& sceneSpec) {
  Diagnostics diags;
  auto result = loadAndCompile(path, size, diags);
  printDiagnostics(diags);
  if (!result || hasErrors(diags)) return kExitFailure;
  if (sceneSpec.empty()) {
    if (json)
      std::cout << planJson(result->second).dump(2) << "\n";
    else
      printPlanText(result->second);
    return kExitOk;
  }
  // Model no more than the scene needs: adapt, then compile again.
  Scene scene;
  try {
    scene = loadSceneAny(sceneSpec);
  } catch (const RuntimeError& e) {
    std::cerr << errorLine(e.what()) << "\n";
    return kExitFailure;
  }
  PipelineConfig adapted = result->first;
  const SceneFeatures features = sceneFeatures(scene, scene.camera, float(size.width) / float(size.height));
  const AdaptReport report = adaptToScene(adapted, registry(), features);
  Diagnostics adaptedDiags;
  Plan plan = checkPipeline(adapted, compileOptions(size.width, size.height, size.maxTextureSize), ShaderChecks::skip,
                            adaptedDiags, /*scenePresent=*/true);
  printDiagnostics(adaptedDiags);
  if (hasErrors(adaptedDiags)) return kExitFailure;
  const uint32_t before = gbufferBytesPerPixel(result->first, result->second, registry());
  const uint32_t after = gbufferBytesPerPixel(adapted, plan, registry());
  if (json) {
    nlohmann::json out = planJson(plan);
    out["scene"] = {{"source", scene.source},
                    {"adaptations", report.notes},
                    {"warnings", scene.warnings},
                    {"shadows", shadowsJson(features)},
                    {"reports", reportsJson(report)},
                    {"gbuffer_bytes_per_pixel", {{"before", before}, {"after", after}}},
                    {"memory_before", memoryJson(result->second)}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "adapted to scene " << scene.source << ":\n";
    if (report.notes.empty()) std::cout << "  (nothing to drop)\n";
    for (const auto& n : report.notes) std::cout << "  " << n << "\n";
    // The loaders' warnings (also on stderr as they happen): what is not drawn.
    if (!scene.warnings.empty()) std::cout << "scene warnings:\n";
    for (const auto& w : scene.warnings) std::cout << "  " << w << "\n";
    printShadows(features);
    for (const AdaptReport::Table& t : report.tables) {
      std::cout << "pass '" << t.pass << "' reports:\n";
      for (const std::string& line : t.lines) std::cout << "  " << line << "\n";
    }
    std::cout << "G-buffer bytes per pixel: " << before << " before, " << after << " after\n";
    printPlanText(plan);
  }
  return kExitOk;
}

int runDot(const std::string& path, const SizeOptions& size) {
  Diagnostics diags;
  auto result = loadAndCompile(path, size, diags);
  printDiagnostics(diags);
  if (!result || hasErrors(diags)) return kExitFailure;
  std::cout << toDot(result->first.graph, result->second);
  return kExitOk;
}

}  // namespace rgraph::cli
