#version 450 core
// Line 3 includes a file that does not exist.
#include "include/no_such_include.glsl"
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(1.0); }
