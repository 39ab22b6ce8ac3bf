// What the procedural scenes' source files share (procedural.cpp,
// procedural_walker.cpp).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/scene.h"

namespace rgraph {

// Appends a primitive drawing mesh `mesh` with `material` at `xf`, its
// bounds the mesh's under `xf`.
void addDraw(Scene& s, int mesh, int material, const glm::mat4& xf, const std::string& name);

// The flat-coloured scenes (thin, walker): a dielectric material of one
// colour (its index), and point lights falling off as 1 / (1 + 0.22 d +
// 0.2 d^2) with their radius from that, one per position and colour.
int addFlatMaterial(Scene& s, const std::string& name, glm::vec3 color, float specular, float roughness);
void addFalloffLights(Scene& s, const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& colors);
// The scene's camera: 45 degree fov, near 0.1.
void placeCamera(Scene& s, glm::vec3 position, glm::vec3 target, float far);

}  // namespace rgraph
