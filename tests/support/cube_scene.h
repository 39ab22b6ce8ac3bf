// Small hand-built scenes shared by test suites that need one object (or a
// row of cubes) whose pixels and features a test can predict. GL-free.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/scene.h"

namespace rgraph::testsupport {

// One primitive: `mesh` (mesh 0) drawn with `material` (material 0) where the
// mesh stands (identity transform; bounds: the mesh's). No light, no camera.
inline Scene singleMeshScene(MeshData mesh, Material material = {}) {
  Scene s;
  s.meshes.push_back(std::move(mesh));
  s.materials.push_back(std::move(material));
  Primitive p;
  p.mesh = 0;
  p.material = 0;
  p.bounds = s.meshes[0].bounds;
  s.primitives.push_back(p);
  return s;
}

// Gives `s` its camera at `eye`, looking at the origin (the Camera's other defaults).
inline void lookAtOrigin(Scene& s, glm::vec3 eye) {
  s.camera.position = eye;
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.hasCamera = true;
}

// A cube (edge 1) at each of `places`, named cube0, cube1, ... in order, of
// one material (base colour (0.8, 0.5, 0.3)), seen from (0, 0, 5) looking
// down -z (fovY 45) under a directional light; no point light (no light
// volumes).
inline Scene cubesScene(const std::vector<glm::vec3>& places) {
  Material clay;
  clay.baseColorFactor = glm::vec4(0.8f, 0.5f, 0.3f, 1.0f);
  Scene s = singleMeshScene(makeCube(0.5f), clay);
  s.source = "cubes";
  const Primitive cube = s.primitives.front();
  s.primitives.clear();
  for (size_t i = 0; i < places.size(); ++i) {
    Primitive p = cube;
    p.transform = glm::translate(glm::mat4(1.0f), places[i]);
    p.bounds = p.worldBounds(s.meshes[0].bounds);
    p.name = "cube" + std::to_string(i);
    s.primitives.push_back(p);
  }
  s.directionalLights.push_back(DirectionalLight{glm::normalize(glm::vec3(-0.3f, -0.6f, -1.0f)), glm::vec3(1.0f), 1.0f});
  lookAtOrigin(s, {0.0f, 0.0f, 5.0f});
  s.camera.fovY = 45.0f;
  return s;
}

}  // namespace rgraph::testsupport
