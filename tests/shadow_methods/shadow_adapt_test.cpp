// How every lighting pass type adapts its shadow inputs to a scene
// (shadows::declareReader): with a caster and a casting light it keeps
// "shadows" and its inputs; with no caster, no casting light in view, its
// own hook disabling it, or (forward) nothing blended to light, it turns
// "shadows" off and unbinds them with a note, so that no shadow map is kept
// alive for it and its shadow code is compiled out. The features are stated
// here, not derived from a scene: these are the lighting passes' hooks alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rgraph/adapt.h"
#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/pipeline_load.h"

namespace {
using namespace rgraph;

const std::string kDir = std::string(RGRAPH_SOURCE_DIR) + "/tests/shadow_methods/pipelines/";

PipelineConfig load(const std::string& name) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(kDir + name, diags);
  PipelineConfig cfg = doc.build(processRegistry(), diags);
  EXPECT_FALSE(hasErrors(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  return cfg;
}

// A scene with casters, a sun and a point light that cast, BLEND materials.
SceneFeatures castingFeatures() {
  SceneFeatures f;
  f.shadowCasters = true;
  f.shadowLights = {{SceneFeatures::ShadowLight::Kind::directional, 0},
                    {SceneFeatures::ShadowLight::Kind::point, 0}};
  return f;
}

bool bindsShadows(const PassDecl& p) {
  return std::any_of(p.uses.begin(), p.uses.end(), [](const ResourceUse& u) {
    return u.slot == "shadows" || u.slot == "shadow_info" || u.slot == "shadow_depths" || u.slot == "shadow_moments";
  });
}

// The lighting passes (every pass that declares the "shadows" param).
std::vector<size_t> lightingPasses(const PipelineConfig& cfg) {
  std::vector<size_t> out;
  for (size_t i = 0; i < cfg.graph.passes.size(); ++i)
    if (cfg.graph.passes[i].type != "shadow_map" && cfg.params[i].has("shadows")) out.push_back(i);
  return out;
}

const char* const kPipelines[] = {"fullscreen.json", "light-volumes.json", "tiled.json", "clustered.json",
                                  "forward-lit.json", "forward-plus.json"};

TEST(ShadowAdapt, ACastingSceneKeepsEveryLightingPassShadowed) {
  for (const char* name : kPipelines) {
    SCOPED_TRACE(name);
    PipelineConfig cfg = load(name);
    adaptToScene(cfg, processRegistry(), castingFeatures());
    const std::vector<size_t> lit = lightingPasses(cfg);
    ASSERT_FALSE(lit.empty());
    for (size_t i : lit) {
      SCOPED_TRACE(cfg.graph.passes[i].name);
      EXPECT_TRUE(cfg.params[i].getBool("shadows"));
      EXPECT_TRUE(bindsShadows(cfg.graph.passes[i]));
    }
  }
}

void expectCompiledOut(const SceneFeatures& f, const std::string& reason) {
  for (const char* name : kPipelines) {
    SCOPED_TRACE(name);
    PipelineConfig cfg = load(name);
    const AdaptReport r = adaptToScene(cfg, processRegistry(), f);
    for (size_t i : lightingPasses(cfg)) {
      const std::string& pass = cfg.graph.passes[i].name;
      SCOPED_TRACE(pass);
      EXPECT_FALSE(cfg.params[i].getBool("shadows"));
      EXPECT_FALSE(bindsShadows(cfg.graph.passes[i]));
      const std::string note = "pass '" + pass + "': " + reason + ": shadow code compiled out";
      EXPECT_NE(std::find(r.notes.begin(), r.notes.end(), note), r.notes.end()) << "no note '" << note << "'";
    }
  }
}

TEST(ShadowAdapt, NoCasterCompilesEveryLightingPassesShadowsOut) {
  SceneFeatures f = castingFeatures();
  f.shadowCasters = false;
  f.shadowLights.clear();
  expectCompiledOut(f, "no primitive casts a shadow");
}

TEST(ShadowAdapt, NoCastingLightInViewCompilesEveryLightingPassesShadowsOut) {
  SceneFeatures f = castingFeatures();
  f.shadowLights.clear();
  expectCompiledOut(f, "no casting light reaches the view");
}

TEST(ShadowAdapt, ThePassTypesOwnHookRunsFirst) {
  // No point lights: light_volumes' own hook disables it (a disabled pass
  // reads nothing, whatever it binds); the ambient-and-sun pass keeps the
  // sun's shadow.
  PipelineConfig cfg = load("light-volumes.json");
  SceneFeatures f = castingFeatures();
  f.pointLights = false;
  f.shadowLights.pop_back();  // the sun alone
  const AdaptReport r = adaptToScene(cfg, processRegistry(), f);
  for (size_t i : lightingPasses(cfg)) {
    const PassDecl& p = cfg.graph.passes[i];
    SCOPED_TRACE(p.name);
    EXPECT_EQ(p.enabled, p.type != "light_volumes");
    if (p.enabled) EXPECT_TRUE(cfg.params[i].getBool("shadows") && bindsShadows(p));
  }
  for (const std::string& note : r.notes) EXPECT_EQ(note.find("shadow code"), std::string::npos) << note;
}

TEST(ShadowAdapt, AForwardPassWithNothingBlendedDropsItsShadowInputs) {
  PipelineConfig cfg = load("fullscreen.json");
  for (size_t i = 0; i < cfg.graph.passes.size(); ++i)
    if (cfg.graph.passes[i].type == "forward") cfg.params[i].set("markers", true);  // still enabled: its markers
  SceneFeatures f = castingFeatures();
  f.blendMaterials = false;
  const AdaptReport r = adaptToScene(cfg, processRegistry(), f);
  for (size_t i : lightingPasses(cfg)) {
    SCOPED_TRACE(cfg.graph.passes[i].name);
    const bool forward = cfg.graph.passes[i].type == "forward";
    EXPECT_EQ(cfg.params[i].getBool("shadows"), !forward);
    EXPECT_EQ(bindsShadows(cfg.graph.passes[i]), !forward);
  }
  const std::string note = "pass 'forward': no BLEND materials: shadow code compiled out";
  EXPECT_NE(std::find(r.notes.begin(), r.notes.end(), note), r.notes.end()) << "no note '" << note << "'";
}

// EVSM (pipelines/deferred-pbr-shadows-evsm.json): the shadow_moments
// template becomes one instance and sizes its moments and scratch for every
// casting light in view (4 layers for the sun, 6 for a point light); with no
// casting light it is removed, as the atlas's writers are, and the lighting
// pass unbinds the moments.
const ResourceDecl& resource(const PipelineConfig& cfg, const std::string& name) {
  auto it = std::find_if(cfg.graph.resources.begin(), cfg.graph.resources.end(),
                         [&](const ResourceDecl& r) { return r.name == name; });
  EXPECT_NE(it, cfg.graph.resources.end()) << name;
  return *it;
}

PipelineConfig loadEvsm() {
  Diagnostics diags;
  ConfigDocument doc =
      ConfigDocument::parseFile(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-pbr-shadows-evsm.json", diags);
  PipelineConfig cfg = doc.build(processRegistry(), diags);
  EXPECT_FALSE(hasErrors(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  return cfg;
}

TEST(ShadowAdapt, EvsmMomentsAreSizedForEveryCastingLight) {
  PipelineConfig cfg = loadEvsm();
  adaptToScene(cfg, processRegistry(), castingFeatures());
  std::vector<std::string> moments;
  for (const PassDecl& p : cfg.graph.passes)
    if (p.type == "shadow_moments") moments.push_back(p.name);
  EXPECT_EQ(moments, std::vector<std::string>{"moments.blur"});
  for (const char* name : {"shadowMoments", "shadowScratch"}) {
    SCOPED_TRACE(name);
    const ResourceDecl& r = resource(cfg, name);
    EXPECT_EQ(r.texture.layers, 10u);  // the sun's 4 cascades and a point light's 6 faces, as the atlas
    EXPECT_EQ(r.texture.size.width, 512u);
    EXPECT_EQ(r.texture.layers, resource(cfg, "shadowAtlas").texture.layers);
  }
  for (size_t i : lightingPasses(cfg))
    if (cfg.params[i].getBool("shadows")) EXPECT_EQ(cfg.params[i].getString("shadow_filter"), "evsm");
}

TEST(ShadowAdapt, EvsmMomentsAreRemovedWithNoCastingLight) {
  PipelineConfig cfg = loadEvsm();
  SceneFeatures f = castingFeatures();
  f.shadowLights.clear();
  const AdaptReport r = adaptToScene(cfg, processRegistry(), f);
  for (const PassDecl& p : cfg.graph.passes) {
    EXPECT_NE(p.type, "shadow_moments");
    EXPECT_FALSE(bindsShadows(p)) << p.name;
  }
  const std::string note = "pass 'moments': removed (no casting light reaches the view: no shadow moments)";
  EXPECT_NE(std::find(r.notes.begin(), r.notes.end(), note), r.notes.end()) << "no note '" << note << "'";
}

}  // namespace
