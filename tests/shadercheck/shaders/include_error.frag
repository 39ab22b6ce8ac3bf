#version 450 core
// The error is on line 3 of include/bad_include.glsl, not here.
#include "include/bad_include.glsl"
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(helper()); }
