#version 450 core
// FXAA, after the ideas of Lottes' FXAA 3.11 quality preset (written anew):
//  1. local contrast: the luma range of the pixel and its 4 neighbours; below
//     max(u_contrastThreshold, u_relativeThreshold * brightest) the pixel is
//     not on an edge and is written unchanged (flat regions stay exact);
//  2. edge orientation from second differences over the 3x3 block;
//  3. the side of the edge (the neighbour across it with the larger step);
//     when the pixel across is a line one pixel thin (the pixel beyond it is
//     back on this pixel's side of the edge's mean), there is no step edge
//     between the two to place: the line's coverage hardly reaches this pixel,
//     so it gets no edge blend (step 4 is skipped; step 5 still applies);
//  4. a search along the edge, on the boundary between the two rows (bilinear
//     taps average them), in growing steps until the luma leaves the edge's
//     mean by a quarter of its step: the nearer end says how far this pixel
//     sits from where the staircase step is, hence how much to blend;
//  5. a sub-pixel term (the pixel against its 3x3 low-pass) for features
//     thinner than a pixel, which have no edge to search along.
// The result is one bilinear tap moved across the edge by the larger offset.
in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_input;
uniform float u_contrastThreshold;  // absolute: below this luma range nothing is filtered (dark areas)
uniform float u_relativeThreshold;  // relative to the brightest luma of the cross
uniform float u_subpixel;           // 0 off .. 1 full sub-pixel blending
uniform int u_linearInput;          // 1: the input decodes to linear (sRGB texture): luma is re-encoded
layout(location = 0) out vec4 outColor;

// Step sizes of the search, in pixels (the quality preset's growing schedule).
const int kSteps = 12;
const float kStepSize[kSteps] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);

float luma(vec3 c) {
  float l = dot(c, vec3(0.299, 0.587, 0.114));
  // Edges are judged on perceptual values: an sRGB texture reads back linear.
  return u_linearInput != 0 ? sqrt(max(l, 0.0)) : l;
}
float lumaAt(vec2 uv) { return luma(textureLod(u_input, uv, 0.0).rgb); }
float lumaOff(ivec2 p, ivec2 o) {
  ivec2 size = textureSize(u_input, 0);
  return luma(texelFetch(u_input, clamp(p + o, ivec2(0), size - 1), 0).rgb);
}

// Step 4: the blend of pixel `p` towards the pixel across its edge (luma m,
// edge mean edgeLuma, larger step gradient); `along` and `toEdge` are the
// uv steps along the edge and from the pixel centre to the edge.
float edgeBlend(ivec2 p, vec2 texel, vec2 along, vec2 toEdge, float m, float edgeLuma, float gradient) {
  // Walk along the boundary between this pixel and the one across.
  vec2 uvCenter = (vec2(p) + 0.5) * texel;
  float stopAt = 0.25 * gradient;
  vec2 uvNeg = uvCenter + toEdge - along, uvPos = uvCenter + toEdge + along;
  float dNeg = lumaAt(uvNeg) - edgeLuma, dPos = lumaAt(uvPos) - edgeLuma;
  bool doneNeg = abs(dNeg) >= stopAt, donePos = abs(dPos) >= stopAt;
  for (int i = 1; i < kSteps && !(doneNeg && donePos); ++i) {
    if (!doneNeg) {
      uvNeg -= along * kStepSize[i];
      dNeg = lumaAt(uvNeg) - edgeLuma;
      doneNeg = abs(dNeg) >= stopAt;
    }
    if (!donePos) {
      uvPos += along * kStepSize[i];
      dPos = lumaAt(uvPos) - edgeLuma;
      donePos = abs(dPos) >= stopAt;
    }
  }
  float distNeg = dot(uvCenter - uvNeg, along) / dot(along, along);  // in pixels
  float distPos = dot(uvPos - uvCenter, along) / dot(along, along);
  float dEnd = distNeg < distPos ? dNeg : dPos;
  // Blend only when the nearer end is where this pixel's side of the edge
  // ends (its luma crosses the edge mean the other way than this pixel's).
  bool consistent = ((m - edgeLuma) < 0.0) != (dEnd < 0.0);
  return consistent ? 0.5 - min(distNeg, distPos) / (distNeg + distPos) : 0.0;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 texel = 1.0 / vec2(textureSize(u_input, 0));
  vec4 center = texelFetch(u_input, p, 0);
  float m = luma(center.rgb);
  float n = lumaOff(p, ivec2(0, 1)), s = lumaOff(p, ivec2(0, -1));
  float e = lumaOff(p, ivec2(1, 0)), w = lumaOff(p, ivec2(-1, 0));
  float lo = min(m, min(min(n, s), min(e, w)));
  float hi = max(m, max(max(n, s), max(e, w)));
  float range = hi - lo;
  if (range < max(u_contrastThreshold, hi * u_relativeThreshold)) {
    outColor = center;  // not an edge: exactly the input
    return;
  }
  float ne = lumaOff(p, ivec2(1, 1)), nw = lumaOff(p, ivec2(-1, 1));
  float se = lumaOff(p, ivec2(1, -1)), sw = lumaOff(p, ivec2(-1, -1));

  // Sub-pixel aliasing: how far the pixel stands out of its low-pass, shaped
  // by a smoothstep and squared so that only clear outliers blend much.
  float lowPass = (2.0 * (n + s + e + w) + (ne + nw + se + sw)) / 12.0;
  float sub = clamp(abs(lowPass - m) / range, 0.0, 1.0);
  sub = sub * sub * (3.0 - 2.0 * sub);
  float subOffset = sub * sub * u_subpixel;

  // Orientation: a horizontal edge changes along y (second differences in y).
  float edgeH = 2.0 * abs(n + s - 2.0 * m) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
  float edgeV = 2.0 * abs(e + w - 2.0 * m) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
  bool horizontal = edgeH >= edgeV;

  // The side across the edge: the neighbour with the larger step.
  float l1 = horizontal ? s : w;  // negative side
  float l2 = horizontal ? n : e;  // positive side
  float g1 = abs(l1 - m), g2 = abs(l2 - m);
  bool negative = g1 >= g2;
  float gradient = max(g1, g2);
  float across = horizontal ? texel.y : texel.x;
  if (negative) across = -across;
  float edgeLuma = 0.5 * (m + (negative ? l1 : l2));
  // A line one pixel thin across (the pixel beyond it is on this side again):
  // no step edge to place between the two (see the top).
  ivec2 acrossPixel = horizontal ? ivec2(0, negative ? -1 : 1) : ivec2(negative ? -1 : 1, 0);
  bool thinLineAcross = (lumaOff(p, 2 * acrossPixel) < edgeLuma) == (m < edgeLuma);

  vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);
  vec2 toEdge = 0.5 * (horizontal ? vec2(0.0, across) : vec2(across, 0.0));
  float edgeOffset = thinLineAcross ? 0.0 : edgeBlend(p, texel, along, toEdge, m, edgeLuma, gradient);

  float offset = max(edgeOffset, subOffset);
  vec2 uv = (vec2(p) + 0.5) * texel;
  if (horizontal) uv.y += offset * across;
  else uv.x += offset * across;
  outColor = vec4(textureLod(u_input, uv, 0.0).rgb, center.a);
}
