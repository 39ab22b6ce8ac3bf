#version 450 core
// Writes depth d = (x + 64 y) / 4096 (exact in float32 for x, y < 64) and
// colour (d, d, d, 1) where x, y are integer pixel coordinates (y = 0 at the bottom).
layout(location = 0) out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float d = float(p.x + 64 * p.y) / 4096.0;
  gl_FragDepth = d;
  o_color = vec4(d, d, d, 1.0);
}
