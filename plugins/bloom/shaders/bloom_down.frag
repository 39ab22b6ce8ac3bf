#version 450 core
// Bloom mip chain, one downsample to half size (Jimenez 2014, "Next
// generation post processing in Call of Duty: Advanced Warfare"): 13 bilinear
// taps, each at a corner between four source texels, grouped into five boxes
// of four taps: the centre box (taps one texel diagonally off the centre)
// weighs 1/2, the four overlapping corner boxes 1/8 each. With u_karis the
// boxes are weighted by 1 / (1 + luma) instead (Karis's average), so that a
// single very bright texel cannot dominate its neighbourhood: the first
// downsample uses it against fireflies that would flicker as they move.
#include "bloom_chain.glsl"

uniform int u_karis;
layout(location = 0) out vec4 outColor;

float luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

void main() {
  vec2 c = sourcePosition();
  vec3 a = tap(c, vec2(-2, -2)), b = tap(c, vec2(0, -2)), d = tap(c, vec2(2, -2));
  vec3 e = tap(c, vec2(-1, -1)), f = tap(c, vec2(1, -1));
  vec3 g = tap(c, vec2(-2, 0)), h = tap(c, vec2(0, 0)), i = tap(c, vec2(2, 0));
  vec3 j = tap(c, vec2(-1, 1)), k = tap(c, vec2(1, 1));
  vec3 l = tap(c, vec2(-2, 2)), m = tap(c, vec2(0, 2)), n = tap(c, vec2(2, 2));
  vec3 boxes[5] = vec3[](e + f + j + k, a + b + g + h, b + d + h + i, g + h + l + m, h + i + m + n);
  const float weights[5] = float[](0.5, 0.125, 0.125, 0.125, 0.125);
  vec3 sum = vec3(0.0);
  float total = 0.0;
  for (int q = 0; q < 5; ++q) {
    vec3 box = boxes[q] * 0.25;
    float w = u_karis != 0 ? weights[q] / (1.0 + luma(box)) : weights[q];
    sum += box * w;
    total += w;
  }
  outColor = vec4(sum / total, 1.0);
}
