#include "uniform_blocks.h"

#include <glslang/Include/Types.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>

namespace rgraph::shadercheck_detail {
namespace {

// "mat4", "vec4", "ivec4", "float", "uvec2", "mat3x4", "vec4[8]", a struct's name...
std::string glslSpelling(const glslang::TType& t) {
  std::string out;
  if (t.isStruct()) {
    out = t.getTypeName().c_str();
  } else {
    const char* prefix = "";
    const char* scalar = "float";
    switch (t.getBasicType()) {
      case glslang::EbtInt: prefix = "i", scalar = "int"; break;
      case glslang::EbtUint: prefix = "u", scalar = "uint"; break;
      case glslang::EbtBool: prefix = "b", scalar = "bool"; break;
      case glslang::EbtDouble: prefix = "d", scalar = "double"; break;
      default: break;
    }
    if (t.isMatrix()) {
      out = std::string(prefix) + "mat" + std::to_string(t.getMatrixCols());
      if (t.getMatrixRows() != t.getMatrixCols()) out += "x" + std::to_string(t.getMatrixRows());
    } else if (t.getVectorSize() > 1) {
      out = std::string(prefix) + "vec" + std::to_string(t.getVectorSize());
    } else {
      out = scalar;
    }
  }
  if (t.isArray()) out += "[" + std::to_string(t.getOuterArraySize()) + "]";
  return out;
}

}  // namespace

std::vector<UniformBlock> reflectUniformBlocks(const glslang::TProgram& program) {
  std::vector<UniformBlock> blocks;
  for (int b = 0; b < program.getNumUniformBlocks(); ++b) {
    const glslang::TObjectReflection& r = program.getUniformBlock(b);
    UniformBlock block;
    block.name = r.name;
    block.binding = r.getBinding();
    block.size = r.size;
    blocks.push_back(std::move(block));
  }
  // A block member's index is its block's.
  for (int i = 0; i < program.getNumUniformVariables(); ++i) {
    const glslang::TObjectReflection& u = program.getUniform(i);
    if (u.index < 0 || u.index >= static_cast<int>(blocks.size()) || !u.getType()) continue;
    blocks[static_cast<size_t>(u.index)].members.push_back(UniformBlockMember{u.name, u.offset, glslSpelling(*u.getType())});
  }
  for (auto& block : blocks)
    std::stable_sort(block.members.begin(), block.members.end(),
                     [](const UniformBlockMember& a, const UniformBlockMember& b) { return a.offset < b.offset; });
  return blocks;
}

}  // namespace rgraph::shadercheck_detail
