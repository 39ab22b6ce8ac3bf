#version 450 core
layout(location = 0) out vec2 o_rg;
void main() { o_rg = vec2(0.5); }
