#version 450 core
#include "common_bad.glsl"
layout(location = 0) out vec4 o_color;

void main() { o_color = vec4(helper(0.5)); }
