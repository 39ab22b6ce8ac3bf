#version 450 core
layout(location = 0) out vec4 o_color;
uniform sampler2D input0;  // declared, never read: binding input0 is fine
void main() { o_color = vec4(1.0); }
