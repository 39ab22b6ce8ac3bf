// The shadow tests' scene and renders: a floor, a box resting on it, a thin
// pillar and a floating slab, no ambient light (a shadowed pixel is black),
// and deferred-pbr-shadows.json with linear output (no tone curve), no light
// markers, and the filter asked for ("": shadows off).
#pragma once

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "rgraph/adapt.h"
#include "rgraph/passes/shadow_views.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"
#include "rgraph/pipeline_load.h"
#include "support/render_util.h"
#include "support/test_support.h"

namespace shadowtest {
using namespace rgraph;

constexpr uint32_t kMapSize = 2048;

inline const char* kindName(shadows::LightKind k) {
  return k == shadows::LightKind::directional ? "directional" : k == shadows::LightKind::spot ? "spot" : "point";
}

inline void addBox(Scene& s, glm::vec3 centre, glm::vec3 halfSize) {
  if (s.meshes.empty()) s.meshes.push_back(makeCube(1.0f));
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.transform = glm::scale(glm::translate(glm::mat4(1.0f), centre), halfSize);
  p.bounds.expand(centre - halfSize);
  p.bounds.expand(centre + halfSize);
  s.primitives.push_back(p);
}

inline Scene testScene() {
  Scene s;
  s.source = "shadow test scene";
  Material m;
  m.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  m.roughnessFactor = 0.9f;
  m.metallicFactor = 0.0f;
  s.materials.push_back(m);
  addBox(s, {0.0f, -0.05f, 0.0f}, {10.0f, 0.05f, 10.0f});  // floor, top at y = 0
  addBox(s, {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.5f});       // box resting on it
  addBox(s, {2.0f, 1.5f, -1.0f}, {0.15f, 1.5f, 0.15f});    // pillar
  addBox(s, {-2.5f, 1.5f, 1.0f}, {0.75f, 0.05f, 0.75f});   // floating slab
  s.ambient = glm::vec3(0.0f);
  s.camera.position = {0.0f, 7.0f, 10.0f};
  s.camera.target = {0.0f, 0.5f, 0.0f};
  s.camera.near = 0.1f;
  s.camera.far = 60.0f;
  s.hasCamera = true;
  return s;
}

inline DirectionalLight sun() {
  DirectionalLight d;
  d.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, -0.35f));
  d.intensity = 0.8f;
  return d;
}

inline PointLight spot() {
  PointLight l;
  l.spot = true;
  l.position = {3.0f, 6.0f, 3.0f};
  l.direction = glm::normalize(glm::vec3(-3.0f, -6.0f, -3.0f));
  l.innerConeDeg = 25.0f;
  l.outerConeDeg = 35.0f;
  l.constant = 1.0f;
  l.linear = 0.0f;
  l.quadratic = 0.01f;
  l.intensity = 1.0f;
  return l;
}

inline PointLight point() {
  PointLight l;
  l.position = {0.8f, 3.0f, 1.2f};
  l.castShadows = true;
  l.constant = 1.0f;
  l.linear = 0.0f;
  l.quadratic = 0.05f;
  l.intensity = 1.2f;
  return l;
}

// deferred-pbr-shadows.json (deferred-pbr-shadows-evsm.json for "evsm":
// its moments pass), linear (tone map none, rgba8 output, no markers),
// shadows with `filter` ("" for none), `edit` applied to the document last.
inline nlohmann::json pipelineDoc(const std::string& filter) {
  std::ifstream in(rtest::repoPath(filter == "evsm" ? "pipelines/deferred-pbr-shadows-evsm.json"
                                                    : "pipelines/deferred-pbr-shadows.json"));
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc = nlohmann::json::parse(text.str());
  doc["resources"]["output"]["format"] = "rgba8";
  for (auto& pass : doc["passes"]) {
    if (pass["name"] == "tonemap") pass["params"] = {{"operator", "none"}, {"gamma", 1.0}};
    if (pass["name"] == "forward") pass["params"]["markers"] = false;
    if (pass["name"] == "lighting") {
      if (filter.empty()) {
        pass["params"]["shadows"] = false;
        pass["inputs"].erase("shadows");
        pass["inputs"].erase("shadow_info");
        pass["inputs"].erase("shadow_depths");
        pass["inputs"].erase("shadow_moments");
      } else {
        pass["params"]["shadow_filter"] = filter;
      }
    }
  }
  return doc;
}

inline rtest::Image renderDoc(const nlohmann::json& doc, const Scene& scene, Extent size, ShaderLibrary& shaders) {
  PipelineConfig cfg = testsupport::buildPipelineOrThrow(doc.dump(), "deferred-pbr-shadows.json (test)");
  const Camera& cam = scene.camera;
  adaptToScene(cfg, processRegistry(),
               sceneFeatures(scene, cam, float(size.width) / float(size.height)));
  return rtest::render(cfg, scene, size, shaders);
}

inline rtest::Image render(const Scene& scene, Extent size, ShaderLibrary& shaders, const std::string& filter) {
  return renderDoc(pipelineDoc(filter), scene, size, shaders);
}

}  // namespace shadowtest
