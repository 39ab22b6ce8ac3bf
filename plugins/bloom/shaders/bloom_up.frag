#version 450 core
// Bloom mip chain, one upsample: a 3x3 tent (weights 1 2 1 by 1 2 1, over
// 16) of bilinear taps u_radius source texels apart, times u_scale. The pass
// blends it additively into the next larger level, which still holds that
// level's downsample, so every level adds its own blur width; the last draw
// writes the sum into the destination.
#include "bloom_chain.glsl"

uniform float u_radius;  // tap spacing in source texels
uniform float u_scale;   // 1 / levels on the last draw (the levels' average), else 1
layout(location = 0) out vec4 outColor;

void main() {
  vec2 c = sourcePosition();
  float r = u_radius;
  vec3 sum = 4.0 * tap(c, vec2(0.0));
  sum += 2.0 * (tap(c, vec2(-r, 0.0)) + tap(c, vec2(r, 0.0)) + tap(c, vec2(0.0, -r)) + tap(c, vec2(0.0, r)));
  sum += tap(c, vec2(-r, -r)) + tap(c, vec2(r, -r)) + tap(c, vec2(-r, r)) + tap(c, vec2(r, r));
  outColor = vec4(sum * (u_scale / 16.0), 1.0);
}
