#include "rgraph/passes/shadow_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rgraph::shadows {

std::string lightLabel(LightKind kind, uint32_t light) {
  const char* k = kind == LightKind::directional ? "directional" : kind == LightKind::spot ? "spot" : "point";
  return k + std::to_string(light);
}

std::string layerLabel(const std::vector<ShadowedLight>& lights, uint32_t layer) {
  static const char* const kFaces[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  for (const ShadowedLight& l : lights) {
    if (layer < l.firstLayer || layer >= l.firstLayer + l.layers) continue;
    const uint32_t i = layer - l.firstLayer;
    const std::string name = lightLabel(l.kind, l.light);
    if (l.kind == LightKind::directional) return name + " cascade " + std::to_string(i);
    if (l.kind == LightKind::point) return name + " face " + kFaces[i % 6];
    return name;
  }
  return {};
}

namespace {

// Nearest and farthest view depth of the scene's bounds, within the camera's planes.
std::array<float, 3> litDepths(const Scene& scene, const Camera& camera) {
  const Bounds b = scene.bounds();
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 c{i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
    const float d = glm::dot(c - camera.position, forward);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  if (b.empty()) lo = camera.near, hi = camera.far;
  lo = std::clamp(lo, camera.near, camera.far);
  hi = std::clamp(hi, camera.near, camera.far);
  return {lo, 0.5f * (lo + hi), hi};
}

// The texel of `light`'s maps at the view-axis point at depth `d`.
float texelAtDepth(const std::vector<ShadowView>& views, const ShadowedLight& light, const Camera& camera, float d,
                   uint32_t resolution) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  const glm::vec3 p = camera.position + forward * d;
  for (const ShadowView& v : views) {
    if (v.layer < light.firstLayer || v.layer >= light.firstLayer + light.layers) continue;
    if (v.kind == LightKind::directional) {
      if (d >= v.splitNear && d < v.splitFar) return texelFootprint(v, p, resolution);
      continue;
    }
    // Spot and point: the map that sees p (inside its clip box, within reach).
    const glm::vec4 clip = v.proj * v.view * glm::vec4(p, 1.0f);
    if (clip.w <= 0.0f) continue;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    if (std::abs(ndc.x) <= 1.0f && std::abs(ndc.y) <= 1.0f && std::abs(ndc.z) <= 1.0f)
      return texelFootprint(v, p, resolution);
  }
  return -1.0f;
}

std::string figure(float v) {
  if (v < 0.0f) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", static_cast<double>(v));
  return buf;
}

}  // namespace

Budget budget(const Scene& scene, const Camera& camera, float aspect, const ShadowSettings& settings,
              const std::vector<ShadowedLight>& lights, uint32_t allocatedLayers, uint32_t bytesPerTexel) {
  Budget b;
  b.depths = litDepths(scene, camera);
  const std::vector<ShadowView> views = shadowViews(scene, camera, aspect, settings, lights);
  for (const ShadowedLight& l : lights) {
    BudgetRow row;
    row.light = lightLabel(l.kind, l.light);
    row.resolution = settings.resolution;
    row.layers = l.layers;
    row.firstLayer = l.firstLayer;
    for (int i = 0; i < 3; ++i) row.texel[i] = texelAtDepth(views, l, camera, b.depths[i], settings.resolution);
    b.layersUsed += l.layers;
    b.rows.push_back(std::move(row));
  }
  b.layersAllocated = std::max(allocatedLayers, b.layersUsed);
  b.bytes = uint64_t(settings.resolution) * settings.resolution * b.layersAllocated * bytesPerTexel;
  return b;
}

std::vector<std::string> budgetTable(const Budget& b) {
  std::vector<std::string> lines;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-14s %10s %7s  world units per texel at view depth %s / %s / %s", "light", "map",
                "layers", figure(b.depths[0]).c_str(), figure(b.depths[1]).c_str(), figure(b.depths[2]).c_str());
  lines.push_back(buf);
  for (const BudgetRow& r : b.rows) {
    const std::string map = std::to_string(r.resolution) + "^2";
    const std::string layers = std::to_string(r.firstLayer) + ".." + std::to_string(r.firstLayer + r.layers - 1);
    std::snprintf(buf, sizeof buf, "%-14s %10s %7s  %s / %s / %s", r.light.c_str(), map.c_str(), layers.c_str(),
                  figure(r.texel[0]).c_str(), figure(r.texel[1]).c_str(), figure(r.texel[2]).c_str());
    lines.push_back(buf);
  }
  std::snprintf(buf, sizeof buf, "atlas: %u of %u layers used, %llu bytes", b.layersUsed, b.layersAllocated,
                static_cast<unsigned long long>(b.bytes));
  lines.push_back(buf);
  for (const auto& u : b.unshadowed) lines.push_back("unshadowed " + u.light + ": " + u.reason);
  return lines;
}

}  // namespace rgraph::shadows
