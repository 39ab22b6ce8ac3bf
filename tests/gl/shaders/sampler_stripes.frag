#version 450 core
// Test shader: with u_color.x == 0, one-texel horizontal stripes (red = row
// parity); otherwise every texel u_color.x (the stripes' average, for the
// smaller mip levels).
uniform vec4 u_color;
layout(location = 0) out vec4 o_color;

void main() {
  float v = u_color.x > 0.0 ? u_color.x : float(int(gl_FragCoord.y) & 1);
  o_color = vec4(v, v, 1.0, 1.0);
}
