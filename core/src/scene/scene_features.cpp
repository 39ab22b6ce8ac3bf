#include "rgraph/pass.h"
#include "rgraph/scene.h"

namespace rgraph {

SceneFeatures sceneFeatures(const Scene& scene) {
  SceneFeatures f;
  f.pointLights = scene.hasPointLights();
  f.blendMaterials = scene.hasBlendMaterials();
  f.normalMaps = scene.hasNormalMaps();
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
  return f;
}

}  // namespace rgraph
