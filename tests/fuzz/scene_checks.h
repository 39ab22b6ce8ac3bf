// What the scene and glTF fuzz targets require of a loaded scene, beyond
// Scene::validate(): numbers the renderer can use. A non-finite transform,
// light or camera would load silently and then draw nothing (or NaNs).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "fuzz_util.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph::fuzz {

template <int N>
bool finite(const glm::vec<N, float>& v) {
  for (int i = 0; i < N; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

inline bool finite(const glm::mat4& m) { return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]); }

// "" when every number the renderer reads is finite, else the first problem.
inline std::string nonFiniteValue(const Scene& s) {
  for (size_t i = 0; i < s.meshes.size(); ++i)
    for (const glm::vec3& p : s.meshes[i].positions)
      if (!finite(p)) return "mesh " + std::to_string(i) + ": a vertex position is not finite";
  for (size_t i = 0; i < s.primitives.size(); ++i) {
    const Primitive& p = s.primitives[i];
    if (!finite(p.transform)) return "primitive " + std::to_string(i) + ": transform is not finite";
    if (!p.bounds.empty() && !(finite(p.bounds.min) && finite(p.bounds.max)))
      return "primitive " + std::to_string(i) + ": world bounds are not finite";
  }
  for (size_t i = 0; i < s.pointLights.size(); ++i) {
    const PointLight& l = s.pointLights[i];
    if (!finite(l.position) || !finite(l.color) || !std::isfinite(l.intensity) || !std::isfinite(l.constant) ||
        !std::isfinite(l.linear) || !std::isfinite(l.quadratic) || std::isnan(l.radius))  // +inf: no falloff
      return "point light " + std::to_string(i) + ": a value is not finite";
  }
  for (size_t i = 0; i < s.directionalLights.size(); ++i) {
    const DirectionalLight& l = s.directionalLights[i];
    if (!finite(l.direction) || !finite(l.color) || !std::isfinite(l.intensity))
      return "directional light " + std::to_string(i) + ": a value is not finite";
  }
  if (!finite(s.ambient)) return "ambient is not finite";
  const Camera& c = s.camera;
  if (!finite(c.position) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.fovY) || !std::isfinite(c.near) ||
      !std::isfinite(c.far))
    return "camera: a value is not finite";
  if (s.hasCamera && !finite(c.viewProjection(1.0f))) return "camera: the view-projection matrix is not finite";
  return "";
}

// Runs a loader into `scene`. A refusal must be a RuntimeError naming `file`
// (returns false); a scene it loads must pass validate() (returns true).
template <class Load>
bool loadNamingTheFile(const std::string& file, Scene& scene, Load&& load) {
  try {
    scene = load();
  } catch (const RuntimeError& e) {
    if (verbose()) std::fprintf(stderr, "refused: %s\n", e.what());
    if (std::string(e.what()).find(file) == std::string::npos)
      fail(std::string("error message does not name the file: ") + e.what());
    return false;
  }
  try {
    scene.validate();
  } catch (const RuntimeError& e) {
    fail(std::string("a loaded scene does not validate: ") + e.what());
  }
  return true;
}

}  // namespace rgraph::fuzz
