#version 450 core
// Test image for bloom: a 10.0 square (8x8 texels) in the middle, 0 elsewhere.
layout(location = 0) out vec4 outColor;
uniform vec2 u_resolution;

void main() {
  vec2 d = abs(gl_FragCoord.xy - u_resolution * 0.5);
  outColor = (d.x < 4.0 && d.y < 4.0) ? vec4(10.0, 10.0, 10.0, 1.0) : vec4(0.0, 0.0, 0.0, 1.0);
}
