#version 450 core
out vec4 o_color;  // one output without a location: location 0
void main() { o_color = vec4(1.0); }
