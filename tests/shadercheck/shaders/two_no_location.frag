#version 450 core
out vec4 o_a;
out vec4 o_b;
void main() { o_a = vec4(1.0); o_b = vec4(0.0); }
