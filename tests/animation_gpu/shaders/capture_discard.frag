#version 450 core
// Drawn with the rasterizer off (deform_capture.h): never runs.
out vec4 color;
void main() { color = vec4(1.0); }
