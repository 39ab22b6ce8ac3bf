#version 450 core
// Test shader with a syntax error on line 7.
layout(location = 0) out vec4 o_color;

void main() {
  vec4 c = vec4(1.0);
  c.rgb = c.rgb +* 2.0;
  o_color = c;
}
