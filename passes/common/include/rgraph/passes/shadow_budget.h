// The shadow budget report (`rgraph plan --scene`, the viewer's shadow
// panel): per shadowed light, its maps' resolution and layers and what one
// texel spans on the visible surfaces; the atlas's occupancy and bytes; and
// every light left without a map, with the reason. GL-free, from the same
// views the passes draw (shadow_views.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rgraph/passes/shadow_views.h"

namespace rgraph::shadows {

struct BudgetRow {
  std::string light;  // "directional0", "spot3", "point5"
  uint32_t resolution = 0, layers = 0, firstLayer = 0;
  // World units one texel spans at the near, middle and far lit view depths
  // (Budget::depths); negative where the light's maps do not cover that depth
  // (beyond the last cascade, outside a spot or point light's reach).
  std::array<float, 3> texel{-1.0f, -1.0f, -1.0f};
};

struct Budget {
  std::vector<BudgetRow> rows;
  // The view depths of the visible scene: its bounds' nearest and farthest
  // view depth within the camera's near and far planes, and their middle.
  std::array<float, 3> depths{0.0f, 0.0f, 0.0f};
  uint32_t layersUsed = 0, layersAllocated = 0;
  uint64_t bytes = 0;  // at bytesPerTexel
  struct Unshadowed {
    std::string light, reason;
  };
  std::vector<Unshadowed> unshadowed;
};

// `allocatedLayers` (the atlas's layer count, >= the layers used) and
// `bytesPerTexel` (its format's) size the atlas figure.
Budget budget(const Scene& scene, const Camera& camera, float aspect, const ShadowSettings& settings,
              const std::vector<ShadowedLight>& lights, uint32_t allocatedLayers, uint32_t bytesPerTexel);

// The report as lines of a table (no trailing newlines).
std::vector<std::string> budgetTable(const Budget& b);

std::string lightLabel(LightKind kind, uint32_t light);  // "directional0", "spot3", "point5"

// What atlas layer `layer` holds under the assignment `lights` (the
// expansion's "lights" param): "directional0 cascade 2", "spot3", "point5
// face +y" (faces in ShadowedLight's order); "" for a layer no light owns
// (the spare layer of a one-map atlas).
std::string layerLabel(const std::vector<ShadowedLight>& lights, uint32_t layer);

}  // namespace rgraph::shadows
