#version 450 core
layout(location = 0) out ivec4 o_int;
void main() { o_int = ivec4(1); }
