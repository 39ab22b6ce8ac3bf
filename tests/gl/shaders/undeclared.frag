#version 450 core
// Test shader using an undeclared identifier on line 6.
layout(location = 0) out vec4 o_color;

void main() {
  o_color = vec4(undeclared_thing, 1.0);
}
