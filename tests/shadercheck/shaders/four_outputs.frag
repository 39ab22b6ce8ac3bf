#version 450 core
// Writes four colour outputs (locations 0..3): bound to a pass with only
// three colour attachments, validate must fail.
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_color1;
layout(location = 2) out vec4 o_color2;
layout(location = 3) out vec4 o_color3;

void main() {
  o_color = vec4(1.0, 0.0, 0.0, 1.0);
  o_color1 = vec4(0.0, 1.0, 0.0, 1.0);
  o_color2 = vec4(0.0, 0.0, 1.0, 1.0);
  o_color3 = vec4(1.0);
}
