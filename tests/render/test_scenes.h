// Hand-built scenes shared by the image tests.
#pragma once

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/scene.h"

namespace rgraph::rtest {

inline int addMaterial(Scene& s, glm::vec4 color, float metallic, float roughness, float specular = 0.5f,
                       AlphaMode mode = AlphaMode::opaque) {
  Material m;
  m.name = "material" + std::to_string(s.materials.size());
  m.baseColorFactor = color;
  m.metallicFactor = metallic;
  m.roughnessFactor = roughness;
  m.specular = specular;
  m.alphaMode = mode;
  s.materials.push_back(m);
  return static_cast<int>(s.materials.size()) - 1;
}

inline int addMesh(Scene& s, MeshData mesh) {
  mesh.updateBounds();
  s.meshes.push_back(std::move(mesh));
  return static_cast<int>(s.meshes.size()) - 1;
}

inline void addDraw(Scene& s, int mesh, int material, const glm::mat4& xf, const std::string& name = {}) {
  Primitive p;
  p.mesh = mesh;
  p.material = material;
  p.transform = xf;
  p.bounds = s.meshes[static_cast<size_t>(mesh)].bounds.transformed(xf);
  p.name = name.empty() ? "draw" + std::to_string(s.primitives.size()) : name;
  s.primitives.push_back(std::move(p));
}

inline PointLight pointLight(glm::vec3 pos, glm::vec3 color, float intensity = 1.0f, float linear = 0.7f,
                             float quadratic = 1.8f) {
  PointLight l;
  l.position = pos;
  l.color = color;
  l.intensity = intensity;
  l.constant = 1.0f;
  l.linear = linear;
  l.quadratic = quadratic;
  l.radius = lightRadius(l);
  return l;
}

inline glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }

// A small PBR still life: a floor, three spheres from dielectric-rough to
// metal-smooth, a rotated cube, a half-transparent (BLEND) cube in front, six
// coloured point lights and a directional light.
inline Scene makeCookTorranceScene() {
  Scene s;
  s.source = "test:cook-torrance";
  const int plane = addMesh(s, makePlane(4.0f, 4.0f));
  const int sphere = addMesh(s, makeUvSphere(0.6f, 48, 24));
  const int cube = addMesh(s, makeCube(0.5f));
  const int floorMat = addMaterial(s, {0.55f, 0.55f, 0.5f, 1.0f}, 0.0f, 0.8f);
  addDraw(s, plane, floorMat, translate({0.0f, -1.0f, 0.0f}), "floor");
  const glm::vec4 colors[3] = {{0.9f, 0.2f, 0.15f, 1.0f}, {0.2f, 0.8f, 0.3f, 1.0f}, {0.95f, 0.8f, 0.4f, 1.0f}};
  const float metallic[3] = {0.0f, 0.5f, 1.0f}, roughness[3] = {0.9f, 0.5f, 0.2f};
  for (int i = 0; i < 3; ++i)
    addDraw(s, sphere, addMaterial(s, colors[i], metallic[i], roughness[i]),
            translate({-1.5f + 1.5f * static_cast<float>(i), -0.4f, 0.0f}), "sphere" + std::to_string(i));
  addDraw(s, cube, addMaterial(s, {0.3f, 0.4f, 0.9f, 1.0f}, 0.2f, 0.35f),
          glm::rotate(translate({0.4f, -0.5f, -1.6f}), glm::radians(30.0f), glm::vec3(0, 1, 0)), "cube");
  addDraw(s, cube, addMaterial(s, {0.9f, 0.9f, 0.95f, 0.45f}, 0.0f, 0.3f, 0.5f, AlphaMode::blend),
          glm::scale(translate({-0.8f, -0.6f, 1.4f}), glm::vec3(0.8f)), "glass");

  s.pointLights.push_back(pointLight({-2.0f, 0.6f, 1.5f}, {1.0f, 0.6f, 0.3f}, 3.0f, 0.35f, 0.44f));
  s.pointLights.push_back(pointLight({2.0f, 0.8f, 1.2f}, {0.3f, 0.6f, 1.0f}, 3.0f, 0.35f, 0.44f));
  s.pointLights.push_back(pointLight({0.0f, 1.5f, -0.5f}, {1.0f, 1.0f, 1.0f}, 2.0f, 0.35f, 0.44f));
  s.pointLights.push_back(pointLight({0.8f, -0.6f, 1.0f}, {0.9f, 0.2f, 0.9f}, 1.5f, 0.7f, 1.8f));
  s.pointLights.push_back(pointLight({-0.7f, -0.7f, -1.0f}, {0.2f, 1.0f, 0.4f}, 1.5f, 0.7f, 1.8f));
  s.pointLights.push_back(pointLight({1.8f, -0.2f, -2.0f}, {1.0f, 0.9f, 0.2f}, 2.0f, 0.35f, 0.44f));
  DirectionalLight sun;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  sun.color = glm::vec3(1.0f, 0.95f, 0.9f);
  sun.intensity = 0.6f;
  s.directionalLights.push_back(sun);
  s.ambient = glm::vec3(0.05f);
  s.camera.position = glm::vec3(0.0f, 1.2f, 4.5f);
  s.camera.target = glm::vec3(0.0f, -0.4f, 0.0f);
  s.camera.fovY = 50.0f;
  s.camera.near = 0.1f;
  s.camera.far = 30.0f;
  s.hasCamera = true;
  return s;
}

}  // namespace rgraph::rtest
