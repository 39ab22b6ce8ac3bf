#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/glm.hpp>

#include "rgraph/pass.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

using ShadowLight = SceneFeatures::ShadowLight;

// The six planes of the camera's view frustum (xyz inward unit normal, w the
// offset): a point p is inside a plane when dot(xyz, p) + w >= 0.
std::array<glm::vec4, 6> frustumPlanes(const Camera& camera, float aspect) {
  const glm::mat4 m = camera.viewProjection(aspect);
  const glm::vec4 row[4] = {{m[0][0], m[1][0], m[2][0], m[3][0]},
                            {m[0][1], m[1][1], m[2][1], m[3][1]},
                            {m[0][2], m[1][2], m[2][2], m[3][2]},
                            {m[0][3], m[1][3], m[2][3], m[3][3]}};
  std::array<glm::vec4, 6> planes = {row[3] + row[0], row[3] - row[0], row[3] + row[1],
                                     row[3] - row[1], row[3] + row[2], row[3] - row[2]};
  for (glm::vec4& p : planes) {
    const float len = glm::length(glm::vec3(p));
    if (len > 0.0f) p /= len;
  }
  return planes;
}

// Conservative: a sphere behind no plane may still miss a frustum corner;
// it then keeps a map it did not need, never loses one it needs.
bool sphereMeetsFrustum(const std::array<glm::vec4, 6>& planes, const glm::vec3& center, float radius) {
  for (const glm::vec4& p : planes)
    if (glm::dot(glm::vec3(p), center) + p.w < -radius) return false;
  return true;
}

// How far a light's shadow matters: its reach (radius, else the cut-off
// distance), no farther than the scene's geometry extends from it.
float shadowReach(const PointLight& light, const Bounds& bounds) {
  float reach = light.radius > 0.0f ? light.radius : lightRadius(light);
  if (bounds.empty()) return reach;
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    farthest = std::max(farthest, glm::length(corner - light.position));
  }
  return std::min(reach, farthest);
}

void addLightFacts(const Scene& scene, const Camera& camera, float aspect, SceneFeatures& f) {
  auto unshadowed = [&](ShadowLight light, const char* reason) { f.unshadowedLights.push_back({light, reason}); };
  const bool casters = f.shadowCasters;
  for (size_t i = 0; i < scene.directionalLights.size(); ++i) {
    const ShadowLight light{ShadowLight::Kind::directional, static_cast<uint32_t>(i)};
    if (!casters) unshadowed(light, "no caster in the scene");
    else if (i > 0) unshadowed(light, "not shaded");  // the lighting passes shade only the first
    else if (!scene.directionalLights[i].castShadows) unshadowed(light, "does not cast");
    else f.shadowLights.push_back(light);
  }
  const std::array<glm::vec4, 6> planes = frustumPlanes(camera, aspect);
  const Bounds bounds = scene.bounds();
  struct Candidate {
    ShadowLight light;
    float distance;
  };
  std::vector<Candidate> kept;
  for (size_t i = 0; i < scene.pointLights.size(); ++i) {
    const PointLight& l = scene.pointLights[i];
    const ShadowLight light{l.spot ? ShadowLight::Kind::spot : ShadowLight::Kind::point, static_cast<uint32_t>(i)};
    if (!casters) {
      unshadowed(light, "no caster in the scene");
    } else if (!l.castsShadows()) {
      unshadowed(light, "does not cast");
    } else {
      const float reach = shadowReach(l, bounds);
      if (!sphereMeetsFrustum(planes, l.position, reach)) unshadowed(light, "outside the view");
      else kept.push_back({light, std::max(0.0f, glm::length(l.position - camera.position) - reach)});
    }
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  for (const Candidate& c : kept) f.shadowLights.push_back(c.light);
}

}  // namespace

SceneFeatures sceneFeatures(const Scene& scene) { return sceneFeatures(scene, scene.camera, 16.0f / 9.0f); }

SceneFeatures sceneFeatures(const Scene& scene, const Camera& camera, float aspect) {
  SceneFeatures f;
  f.scene = &scene;
  f.camera = camera;
  f.aspect = aspect;
  f.pointLights = scene.hasPointLights();
  f.blendMaterials = scene.hasBlendMaterials();
  f.normalMaps = scene.hasNormalMaps();
  f.environment = scene.environment.has_value();
  f.metallicRoughnessVariation = scene.hasMetallicRoughnessVariation();
  // The material target also carries ambient occlusion: keep it when any
  // drawn material has an occlusion map.
  for (const auto& p : scene.primitives)
    if (p.material >= 0 && static_cast<size_t>(p.material) < scene.materials.size() &&
        scene.materials[p.material].occlusionTexture.valid())
      f.metallicRoughnessVariation = true;
  if (!f.metallicRoughnessVariation) {
    for (const auto& p : scene.primitives) {
      if (p.material < 0 || static_cast<size_t>(p.material) >= scene.materials.size()) continue;
      f.metallic = scene.materials[p.material].metallicFactor;
      f.roughness = scene.materials[p.material].roughnessFactor;
      break;
    }
  }
  f.lightMarkers = std::any_of(scene.pointLights.begin(), scene.pointLights.end(),
                               [](const PointLight& l) { return l.marker; });
  if (const Bounds b = scene.bounds(); !b.empty()) f.markerSizeLimit = b.radius() * SceneFeatures::kMarkerScale;
  f.emissive = f.reflectance = false;
  for (const auto& p : scene.primitives) {
    if (p.material < 0 || static_cast<size_t>(p.material) >= scene.materials.size()) continue;
    f.emissive = f.emissive || scene.materials[p.material].emits();
    f.reflectance = f.reflectance || scene.materials[p.material].nonDefaultReflectance();
  }
  f.shadowCasters = scene.hasShadowCasters();
  addLightFacts(scene, camera, aspect, f);
  return f;
}

}  // namespace rgraph
