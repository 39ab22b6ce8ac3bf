// What the procedural scenes' source files share (procedural.cpp,
// procedural_walker.cpp).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "rgraph/scene.h"

namespace rgraph {

// Appends a primitive drawing mesh `mesh` with `material` at `xf`, its
// bounds the mesh's under `xf`.
void addDraw(Scene& s, int mesh, int material, const glm::mat4& xf, const std::string& name);

}  // namespace rgraph
