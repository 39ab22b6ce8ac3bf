#version 450 core
// A known function of the pixel position, exactly representable in 8 bits
// (tests compare it bit for bit): r = 4x mod 256, g = 4y mod 256, b = (x xor y)
// mod 256, a = 1; x, y integer pixel coordinates with y = 0 at the bottom row.
layout(location = 0) out vec4 o_color;
uniform vec2 u_resolution;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_color = vec4(float((p.x * 4) & 255) / 255.0, float((p.y * 4) & 255) / 255.0, float((p.x ^ p.y) & 255) / 255.0, 1.0);
}
