// A uniform of a program, its location looked up once (at setup), so that
// setting it every frame costs no glGetUniformLocation.
//
//   gl::Uniform exposure_;                                      // a member
//   exposure_ = gl::Uniform(ctx.program(0), "u_exposure");      // in setup()
//   exposure_.set(1.5f);                                        // in execute()
//
// A uniform the program does not have (optimised away, or absent with these
// defines) has location -1, and setting it does nothing, as in GL.
#pragma once

#include <cstdint>

namespace rgraph::gl {

class Uniform {
 public:
  Uniform() = default;
  Uniform(uint32_t program, const char* name);  // needs a current context

  bool exists() const { return location_ >= 0; }
  int location() const { return location_; }

  // glProgramUniform* on the program. No double overload on purpose: say
  // float or int (a double argument does not compile).
  void set(float x) const;
  void set(float x, float y) const;
  void set(float x, float y, float z, float w) const;
  void set(int x) const;
  void set(bool x) const { set(x ? 1 : 0); }
  void setVec3Array(const float* xyz, int count) const;

 private:
  uint32_t program_ = 0;
  int location_ = -1;
};

}  // namespace rgraph::gl
