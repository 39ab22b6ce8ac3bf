// Probing a shadowed render against exact visibility: for every second pixel
// the light reaches (its unshadowed value is high enough to tell), the
// surface point the CPU ray caster finds there, what the oracle says of it,
// whether it lies near a shadow edge, and whether the map shadowed it (the
// shadowed frame below half the unshadowed one). Tests fold the probes into
// their own figures.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "shadow_scene.h"
#include "visibility_oracle.h"

namespace shadowtest {

struct ProbeResult {
  oracle::VisibilityOracle::Probe probe;
  oracle::Visibility exact = oracle::Visibility::lit;
  bool nearEdge = false;  // within edgeTexels of a point classified otherwise
  bool mapShadowed = false;
  double lightLevel = 0.0;  // shadowed / unshadowed value (1: fully lit)
  float texel = 0.0f;       // world units per texel of the map covering the point
  int x = 0, row = 0;
};

struct ProbeOptions {
  std::string filter = "hard";
  Extent size{400, 300};
  double edgeTexels = 2.5;  // 2 texels, plus half the texel's own extent
  std::function<void(nlohmann::json&)> edit;  // on the pipeline document, before rendering
  int minLevel = 24;  // skip pixels whose unshadowed value is below this (of 255)
};

// The map texel covering `p`: the cascade its view depth falls in, the spot
// map, or the point light's face its direction selects.
inline float texelAt(const std::vector<shadows::ShadowView>& views, const Camera& cam, const glm::vec3& p) {
  const shadows::ShadowView* pick = &views.front();
  if (views.front().kind == shadows::LightKind::directional) {
    const float depth = glm::dot(p - cam.position, glm::normalize(cam.target - cam.position));
    for (const auto& v : views)
      if (depth >= v.splitNear && depth < v.splitFar) pick = &v;
  } else if (views.front().kind == shadows::LightKind::point) {
    const glm::vec3 d = p - views.front().lightPosition, a = glm::abs(d);
    const int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0 ? 0 : 1) : a.y >= a.z ? (d.y >= 0 ? 2 : 3) : (d.z >= 0 ? 4 : 5);
    pick = &views[static_cast<size_t>(face)];
  }
  return shadows::texelFootprint(*pick, p, kMapSize);
}

// Renders `scene` with and without shadows and calls `visit` per probe.
// `light` is the scene's light the one map `assigned` belongs to.
template <class Light>
void forEachProbe(const Scene& scene, const Light& light, const shadows::ShadowedLight& assigned,
                  const ProbeOptions& o, const std::function<void(const ProbeResult&)>& visit,
                  const std::string& saveAs = {}) {
  ShaderLibrary shaders;
  nlohmann::json on = pipelineDoc(o.filter), off = pipelineDoc("");
  if (o.edit) o.edit(on), o.edit(off);
  const rtest::Image withShadows = renderDoc(on, scene, o.size, shaders);
  const rtest::Image without = renderDoc(off, scene, o.size, shaders);
  if (!saveAs.empty()) rtest::saveImage(withShadows, saveAs);
  const oracle::VisibilityOracle exact(scene);
  shadows::ShadowSettings settings;
  settings.resolution = kMapSize;
  for (const auto& pass : on["passes"])
    if (pass["type"] == "shadow_map" && pass.contains("params")) {
      const auto& p = pass["params"];
      if (p.contains("size")) settings.resolution = p["size"].get<uint32_t>();
      if (p.contains("stabilize")) settings.stabilize = p["stabilize"].get<bool>();
      if (p.contains("cascades")) settings.cascades = p["cascades"].get<uint32_t>();
    }
  const float aspect = float(o.size.width) / float(o.size.height);
  const auto views = shadows::shadowViews(scene, scene.camera, aspect, settings, {assigned});
  const Camera& cam = scene.camera;
  const int w = int(o.size.width), h = int(o.size.height);
  auto probeAt = [&](int x, int row) { return exact.probeAtPixel(cam, w, h, x + 0.5, h - row - 0.5); };
  for (int row = 2; row < h - 2; row += 2)
    for (int x = 2; x < w - 2; x += 2) {
      const glm::ivec3 un = without.rgb(x, row), sh = withShadows.rgb(x, row);
      const int unLevel = std::max({un.r, un.g, un.b});
      if (unLevel < o.minLevel) continue;
      const auto probe = probeAt(x, row);
      if (!probe) continue;
      bool flat = true;  // silhouettes and creases: the neighbours on about the same plane
      for (auto [dx, dr] : {std::pair{2, 0}, {-2, 0}, {0, 2}, {0, -2}}) {
        const auto n = probeAt(x + dx, row + dr);
        if (!n || glm::dot(n->normal, probe->normal) < 0.98) flat = false;  // 11 degrees: a sphere's facets pass
      }
      if (!flat) continue;
      ProbeResult r;
      r.probe = *probe;
      r.exact = exact.classify(*probe, light);
      if (r.exact == oracle::Visibility::outside) continue;
      r.x = x, r.row = row;
      r.texel = texelAt(views, cam, glm::vec3(probe->point));
      const glm::dvec3 n = probe->normal;
      const glm::dvec3 t =
          glm::normalize(glm::cross(n, std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
      const glm::dvec3 b = glm::cross(n, t);
      const double radius = o.edgeTexels * r.texel;
      for (int k = 0; k < 16 && !r.nearEdge; ++k) {
        const double ang = k * 3.14159265358979 / 8.0;
        const oracle::VisibilityOracle::Probe q{probe->point + radius * (std::cos(ang) * t + std::sin(ang) * b), n};
        r.nearEdge = (exact.classify(q, light) == oracle::Visibility::shadowed) != (r.exact == oracle::Visibility::shadowed);
      }
      const int shLevel = std::max({sh.r, sh.g, sh.b});
      r.mapShadowed = shLevel < unLevel / 2;
      r.lightLevel = double(shLevel) / double(unLevel);
      visit(r);
    }
}

struct Agreement {
  int probes = 0, agree = 0, lit = 0, shadowed = 0, edges = 0;
  int falseShadow = 0, falseLight = 0;  // lit but shadowed by the map; shadowed but lit
  double share() const { return probes ? double(agree) / probes : 0.0; }
  void add(const ProbeResult& r) {
    if (r.nearEdge) {
      ++edges;
      return;
    }
    const bool shadow = r.exact == oracle::Visibility::shadowed;
    ++probes;
    (shadow ? shadowed : lit) += 1;
    agree += r.mapShadowed == shadow;
    falseShadow += !shadow && r.mapShadowed;
    falseLight += shadow && !r.mapShadowed;
  }
  void print(const std::string& name) const {
    std::printf("[ measure  ] %s: %d probes (%d lit, %d shadowed, %d near edges left out), %.3f%% agree "
                "(%d lit pixels shadowed, %d shadowed pixels lit)\n",
                name.c_str(), probes, lit, shadowed, edges, 100.0 * share(), falseShadow, falseLight);
  }
};

template <class Light>
Agreement agreement(const Scene& scene, const Light& light, const shadows::ShadowedLight& assigned,
                    const ProbeOptions& o = {}, const std::string& name = {}) {
  Agreement a;
  forEachProbe(scene, light, assigned, o, [&](const ProbeResult& r) { a.add(r); },
               name.empty() ? std::string() : "shadow-" + name);
  if (!name.empty()) a.print(name);
  return a;
}

}  // namespace shadowtest
