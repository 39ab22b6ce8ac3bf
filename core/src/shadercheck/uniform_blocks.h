// Uniform block reflection for ShaderChecker::program (shader_check.cpp):
// every uniform block of a linked program with its members' offsets and GLSL
// types, as glslang lays them out (std140 for the blocks rgraph declares).
#pragma once

#include <vector>

#include "rgraph/shader_check.h"

namespace glslang {
class TProgram;
}

namespace rgraph::shadercheck_detail {

// The program's reflection must have been built with
// EShReflectionAllBlockVariables (members the program does not read count too).
std::vector<UniformBlock> reflectUniformBlocks(const glslang::TProgram& program);

}  // namespace rgraph::shadercheck_detail
