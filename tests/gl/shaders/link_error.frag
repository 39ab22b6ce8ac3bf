#version 450 core
// Compiles, but calls a function that no stage defines: the link fails.
layout(location = 0) out vec4 o_color;
vec4 notDefinedAnywhere();

void main() { o_color = notDefinedAnywhere(); }
