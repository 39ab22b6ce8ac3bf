#version 450 core
// Test images for the bloom oracle (tests/plugin/plugin_oracle_bloom_test.cpp):
//   u_color.z == 0: u_value at the single pixel u_color.xy (GL window
//                   coordinates, origin bottom-left), 0 elsewhere;
//   u_color.z == 1: u_value everywhere;
//   u_color.z == 2: a ramp from 0 to u_value over x + y (nothing larger).
layout(location = 0) out vec4 outColor;
uniform vec4 u_color;
uniform float u_value;
uniform vec2 u_resolution;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float v = 0.0;
  if (u_color.z == 0.0)
    v = px == ivec2(u_color.xy) ? u_value : 0.0;
  else if (u_color.z == 1.0)
    v = u_value;
  else
    v = u_value * float(px.x + px.y) / (u_resolution.x + u_resolution.y - 2.0);
  outColor = vec4(v, v, v, 1.0);
}
