#version 450 core
// The colour held by storage buffer binding 2 (the buffer fixtures: one pass
// binds it there, another reads whatever is bound).
layout(std430, binding = 2) readonly buffer Colour { vec4 u_bufferColor; };
layout(location = 0) out vec4 o_color;
void main() { o_color = u_bufferColor; }
