#version 450 core
// A syntax error on line 7 (a missing semicolon before it is reported there).
layout(location = 0) out vec4 o_color;

void main() {
  vec4 c = vec4(1.0)
  o_color = c;
}
