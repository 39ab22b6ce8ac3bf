// The sampler-type check of the shader checker: a sampler's GLSL type
// against the shape of what its slot binds (2D, a layer or face, 2D array,
// cube, cube array), and a shadow sampler against the slot's compare mode.
#pragma once

#include <string>
#include <vector>

#include "rgraph/shader_check.h"

namespace rgraph {

// What is wrong, one message each (without the pass's name); empty: it fits.
// The messages name the declaration (FILE:LINE); callers place them at the binding.
std::vector<std::string> samplerShapeProblems(const SamplerUniform& s, const SamplerSlot& m, const BoundSlot& b,
                                              const std::string& shader);

}  // namespace rgraph
