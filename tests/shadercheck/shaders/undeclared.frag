#version 450 core
layout(location = 0) out vec4 o_color;

void main() {
  // line 5: an identifier nobody declared
  o_color = vec4(undeclared_thing);
}
