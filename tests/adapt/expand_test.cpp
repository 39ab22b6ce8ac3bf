// Adapt-time expansion (PassAdaptation::expand and ::reshape): a template
// pass replaced by one instance per shadowed light, each writing one layer of
// an atlas its hook reshapes, compiled GL-free with a local registry.
#include <gtest/gtest.h>

#include <algorithm>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/pipeline_check.h"
#include "rgraph/registry.h"

namespace rgraph {
namespace {

using Kind = SceneFeatures::ShadowLight::Kind;

class NoopPass : public PassInstance {
 public:
  void execute(PassContext&) override {}
};

SlotDecl slot(std::string name, Access access, bool required) {
  SlotDecl s;
  s.name = std::move(name);
  s.access = access;
  s.required = required;
  return s;
}

PassTypeDesc passType(std::string name, std::vector<SlotDecl> slots) {
  PassTypeDesc t;
  t.name = std::move(name);
  t.description = "test pass " + t.name;
  t.slots = std::move(slots);
  t.create = [] { return std::make_unique<NoopPass>(); };
  return t;
}

// "shadow_layers": one instance per shadowed light, instance k writing layer
// k of what `map` binds (every instance layer 0 with param "same_layer"),
// the first also reading "aux", the atlas reshaped to as many layers; none:
// the template is removed.
void expandPerLight(const SceneFeatures& f, PassAdaptation& a) {
  if (f.shadowLights.empty()) {
    a.expand.emplace();
    a.notes.push_back("no shadowed light");
    return;
  }
  std::vector<ExpandedPass> instances;
  for (uint32_t k = 0; k < f.shadowLights.size(); ++k) {
    ExpandedPass e;
    e.suffix = "light" + std::to_string(k);
    e.params = a.params;
    e.params.set("layer", int64_t{k});
    Subresource part;
    part.layerBegin = a.params.getBool("same_layer") ? 0 : k;
    part.layerCount = 1;
    e.bindings.push_back({"map", part});
    if (k == 0) e.bindings.push_back({"aux", std::nullopt});  // the first keeps "aux" (and its sampler)
    instances.push_back(std::move(e));
  }
  a.expand = std::move(instances);
  a.reshape.push_back({"map", static_cast<uint32_t>(f.shadowLights.size())});
}

PassRegistry makeRegistry() {
  PassRegistry r;
  PassTypeDesc shadow = passType("shadow_layers", {slot("map", Access::depth_attachment, true),
                                                   slot("aux", Access::sampled, false)});
  ParamDecl same;
  same.name = "same_layer";
  same.type = ParamType::boolean;
  same.defaultValue = false;
  ParamDecl layer;
  layer.name = "layer";
  layer.type = ParamType::integer;
  layer.defaultValue = int64_t{-1};
  shadow.params = {same, layer};
  shadow.adapt = expandPerLight;
  PassTypeDesc light = passType("shade", {slot("shadows", Access::sampled, false), slot("src", Access::sampled, true),
                                          slot("color", Access::color_attachment, true)});
  light.adapt = [](const SceneFeatures& f, PassAdaptation& a) {
    if (!f.shadowLights.empty()) return;
    a.unbindSlots.push_back("shadows");
    a.notes.push_back("no shadowed light: shadows unbound");
  };
  PassTypeDesc fill = passType("fill", {slot("color", Access::color_attachment, true)});
  std::string error;
  EXPECT_TRUE(r.add(std::move(shadow), &error)) << error;
  EXPECT_TRUE(r.add(std::move(light), &error)) << error;
  EXPECT_TRUE(r.add(std::move(fill), &error)) << error;
  return r;
}

// The reader is declared before the template: only its dependencies on the
// instances can order it after them (ties keep declaration order). The
// template's "map" output is on line 10.
std::string pipelineText(bool sameLayer) {
  return std::string(R"({
  "version": 1,
  "resources": {
    "atlas": {"format": "depth32f", "size": [64, 64]},
    "base": {"format": "rgba8"},
    "out": {"format": "rgba8"}
  },
  "passes": [
    {"name": "light", "type": "shade", "inputs": {"shadows": "atlas", "src": "base"}, "outputs": {"color": "out"}},
    {"name": "shadows", "type": "shadow_layers", "inputs": {"aux": "base"}, "outputs": {"map": "atlas"},
     "samplers": {"aux": {"filter": "nearest"}}, "params": {"same_layer": )") +
         (sameLayer ? "true" : "false") + R"(}},
    {"name": "base", "type": "fill", "outputs": {"color": "base"}}
  ],
  "output": "out"
})";
}

PipelineConfig load(const PassRegistry& registry, bool sameLayer = false) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(pipelineText(sameLayer), "expand.json", diags);
  PipelineConfig p = doc.build(registry, diags);
  EXPECT_FALSE(hasErrors(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  return p;
}

SceneFeatures featuresWith(size_t lights) {
  SceneFeatures f;
  f.shadowCasters = true;
  for (uint32_t i = 0; i < lights; ++i) f.shadowLights.push_back({Kind::spot, i});
  return f;
}

std::vector<std::string> passNames(const PipelineConfig& p) {
  std::vector<std::string> names;
  for (const PassDecl& d : p.graph.passes) names.push_back(d.name);
  return names;
}

const ResourceDecl& resourceNamed(const PipelineConfig& p, const std::string& name) {
  auto it = std::find_if(p.graph.resources.begin(), p.graph.resources.end(),
                         [&](const ResourceDecl& r) { return r.name == name; });
  EXPECT_NE(it, p.graph.resources.end()) << name;
  return *it;
}

TEST(AdaptExpand, TemplateBecomesOneInstancePerLightWritingItsLayer) {
  const PassRegistry registry = makeRegistry();
  PipelineConfig p = load(registry);
  const AdaptReport report = adaptToScene(p, registry, featuresWith(3));
  EXPECT_EQ(passNames(p), (std::vector<std::string>{"light", "shadows.light0", "shadows.light1", "shadows.light2",
                                                     "base"}));
  ASSERT_EQ(p.params.size(), 5u);
  // Parallel to the passes, up to the last with overrides (the instances).
  ASSERT_EQ(p.samplers.size(), 4u);
  for (int64_t k = 0; k < 3; ++k) {
    const PassDecl& inst = p.graph.passes[1 + k];
    EXPECT_EQ(inst.type, "shadow_layers");
    EXPECT_EQ(p.params[1 + k].getInt("layer"), k);
    EXPECT_EQ(inst.where.path, "/passes/1");
    // The others keep only "map": "aux" and its sampler override are dropped.
    ASSERT_EQ(inst.uses.size(), k == 0 ? 2u : 1u);
    EXPECT_EQ(inst.uses[0].slot, "map");
    EXPECT_EQ(p.samplers[1 + k].size(), k == 0 ? 1u : 0u);
  }
  EXPECT_EQ(p.samplers[1][0].slot, "aux");
  EXPECT_EQ(p.graph.passes[1].uses[1].slot, "aux");
  EXPECT_TRUE(p.graph.passes[1].uses[1].sub.whole()) << "a binding with no part binds what the template binds";
  EXPECT_EQ(resourceNamed(p, "atlas").texture.layers, 3u);
  ASSERT_FALSE(report.notes.empty());
  EXPECT_EQ(report.notes.back(),
            "pass 'shadows': expanded into 3 passes (shadows.light0, shadows.light1, shadows.light2)");

  const Plan plan = compile(p.graph, CompileOptions{Extent{64, 64}});
  ASSERT_TRUE(plan.ok()) << formatDiagnostic(plan.diagnostics.front());
  EXPECT_EQ(checkPlanContract(plan), "");
  for (uint32_t k = 0; k < 3; ++k) {
    const PlannedPass& inst = plan.passes[1 + k];
    EXPECT_FALSE(inst.culled) << inst.name;
    const BoundUse& map = plan.bindings[1 + k].front();
    EXPECT_EQ(map.slot, "map");
    EXPECT_EQ(map.sub.layerBegin, k);
    EXPECT_EQ(map.sub.layerCount, 1u);
    // The reader, declared first, waits for every instance.
    EXPECT_LT(inst.order, plan.passes[0].order) << inst.name;
  }
  const auto& reads = plan.bindings[0];
  auto shadows = std::find_if(reads.begin(), reads.end(), [](const BoundUse& u) { return u.slot == "shadows"; });
  ASSERT_NE(shadows, reads.end());
  EXPECT_EQ(shadows->sub.layerCount, 3u);
}

TEST(AdaptExpand, InstancesAreNotAdaptedAgain) {
  // Were the instances' hooks run, each would expand into three more.
  const PassRegistry registry = makeRegistry();
  PipelineConfig p = load(registry);
  adaptToScene(p, registry, featuresWith(2));
  EXPECT_EQ(passNames(p), (std::vector<std::string>{"light", "shadows.light0", "shadows.light1", "base"}));
}

TEST(AdaptExpand, NoInstanceRemovesTheTemplateAndTheReaderUnbindsIt) {
  const PassRegistry registry = makeRegistry();
  PipelineConfig p = load(registry);
  const AdaptReport report = adaptToScene(p, registry, featuresWith(0));
  EXPECT_EQ(passNames(p), (std::vector<std::string>{"light", "base"}));
  EXPECT_EQ(p.params.size(), 2u);
  EXPECT_EQ(p.samplers.size(), 1u);  // the template's overrides went with it
  EXPECT_NE(std::find(report.notes.begin(), report.notes.end(), "pass 'shadows': removed (no shadowed light)"),
            report.notes.end());
  EXPECT_EQ(resourceNamed(p, "atlas").texture.layers, 1u);
  const Plan plan = compile(p.graph, CompileOptions{Extent{64, 64}});
  ASSERT_TRUE(plan.ok()) << formatDiagnostic(plan.diagnostics.front());
  // Nothing uses the atlas: no memory for it.
  EXPECT_FALSE(plan.resources[0].physical.valid());
}

TEST(AdaptExpand, DiagnosticsOnInstancesPointAtTheTemplate) {
  const PassRegistry registry = makeRegistry();
  PipelineConfig p = load(registry, /*sameLayer=*/true);
  adaptToScene(p, registry, featuresWith(2));
  PipelineCheckOptions options;
  options.shaders = ShaderCheckMode::skip;
  options.registry = &registry;
  options.scenePresent = true;
  Diagnostics diags;
  const Plan plan = checkPipeline(p, CompileOptions{Extent{64, 64}}, options, diags);
  EXPECT_FALSE(plan.ok());
  auto dup = std::find_if(diags.begin(), diags.end(), [](const Diagnostic& d) {
    return d.code == DiagCode::duplicate_writer && d.message.find("'atlas.layer[0]'") != std::string::npos;
  });
  ASSERT_NE(dup, diags.end()) << (diags.empty() ? "no diagnostics" : formatDiagnostic(diags.front()));
  EXPECT_NE(dup->message.find("pass 'shadows.light0'"), std::string::npos) << dup->message;
  EXPECT_EQ(dup->where.file, "expand.json");
  EXPECT_EQ(dup->where.line, 10) << formatDiagnostic(*dup);
  EXPECT_EQ(dup->where.path, "/passes/1/outputs/map");
}

TEST(AdaptExpand, ImportedTexturesAreNotReshaped) {
  const PassRegistry registry = makeRegistry();
  PipelineConfig p = load(registry);
  for (ResourceDecl& r : p.graph.resources)
    if (r.name == "atlas") r.imported = true;
  const AdaptReport report = adaptToScene(p, registry, featuresWith(2));
  EXPECT_EQ(resourceNamed(p, "atlas").texture.layers, 1u);
  EXPECT_NE(std::find(report.notes.begin(), report.notes.end(),
                      "pass 'shadows': slot 'map' binds 'atlas', imported: not reshaped"),
            report.notes.end());
}

}  // namespace
}  // namespace rgraph
