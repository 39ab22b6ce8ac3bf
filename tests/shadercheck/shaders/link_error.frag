#version 450 core
// Compiles, but never defines main(): the program does not link.
layout(location = 0) out vec4 o_color;
void helper() { o_color = vec4(1.0); }
