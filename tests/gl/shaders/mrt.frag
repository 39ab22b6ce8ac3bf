#version 450 core
// Test shader: u_color into location 0, 1 - u_color into location 1.
layout(location = 0) out vec4 o_a;
layout(location = 1) out vec4 o_b;
uniform vec4 u_color;

void main() {
  o_a = u_color;
  o_b = vec4(1.0 - u_color.rgb, u_color.a);
}
