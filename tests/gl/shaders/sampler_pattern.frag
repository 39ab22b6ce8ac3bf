#version 450 core
// Test shader: texel (x, y) of a small texture holds (x / 4, y / 4, 1, 1),
// exact in every format the sampler tests use.
layout(location = 0) out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_color = vec4(float(p.x) * 0.25, float(p.y) * 0.25, 1.0, 1.0);
}
