#include "rgraph/gl/uniform.h"

#include <GL/glcorearb.h>

namespace rgraph::gl {

Uniform::Uniform(uint32_t program, const char* name)
    : program_(program), location_(program ? glGetUniformLocation(program, name) : -1) {}

void Uniform::set(float x) const {
  if (location_ >= 0) glProgramUniform1f(program_, location_, x);
}

void Uniform::set(float x, float y) const {
  if (location_ >= 0) glProgramUniform2f(program_, location_, x, y);
}

void Uniform::set(float x, float y, float z, float w) const {
  if (location_ >= 0) glProgramUniform4f(program_, location_, x, y, z, w);
}

void Uniform::set(int x) const {
  if (location_ >= 0) glProgramUniform1i(program_, location_, x);
}

void Uniform::setVec3Array(const float* xyz, int count) const {
  if (location_ >= 0) glProgramUniform3fv(program_, location_, count, xyz);
}

}  // namespace rgraph::gl
