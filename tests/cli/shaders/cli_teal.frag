#version 450 core
// A shader outside the built-in folder, for --shader-path tests.
layout(location = 0) out vec4 o_color;

void main() { o_color = vec4(0.0, 0.5, 0.5, 1.0); }
