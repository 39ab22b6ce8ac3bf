#version 450 core
#include "common_ok.glsl"
layout(location = 0) out vec4 o_color;
uniform vec4 u_color;

void main() {
#ifdef DOUBLE
  o_color = u_color;
#else
  o_color = halfOf(u_color);
#endif
}
