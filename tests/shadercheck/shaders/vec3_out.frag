#version 450 core
layout(location = 0) out vec3 o_rgb;
void main() { o_rgb = vec3(0.5); }
