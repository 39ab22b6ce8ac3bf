#version 450 core
// shadow_moments: the EVSM moments of one atlas layer. MOMENTS_CONVERT:
// each moments texel averages the warped depths of the atlas texels it
// covers (the atlas's size over the moments', square). Otherwise a box blur
// of u_source's layer along u_direction (x, then y: separable). Moments:
// (e, e^2, n, n^2) with e = exp(c+ x), n = -exp(-c- x) (shadows.glsl's
// evsmWarp). Each draws layer u_layer of its target, texel for texel.
#include "include/shadows.glsl"

layout(location = 0) out vec4 o_moments;
uniform int u_layer;
uniform ivec2 u_momentsSize;  // texels of one moments layer

#if defined(MOMENTS_CONVERT)
layout(binding = 0) uniform sampler2DArray u_depths;

void main() {
  ivec2 dst = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_depths, 0).xy;
  // The layer's map: a perspective map's depths are linearised first.
  int kind = 0;
  float near = 0.0, far = 1.0;
  for (int m = 0; m < u_shadowCounts.x; ++m) {
    ivec4 l = shadowMaps[m].layers;
    if (u_layer >= l.x && u_layer < l.x + l.y) {
      kind = l.z;
      near = shadowMaps[m].texel.y;
      far = shadowMaps[m].light.w;
      break;
    }
  }
  int ratio = max(size.x / u_momentsSize.x, 1);
  ivec2 origin = dst * size / u_momentsSize;
  vec4 sum = vec4(0.0);
  for (int by = 0; by < ratio; ++by)
    for (int bx = 0; bx < ratio; ++bx) {
      float d = texelFetch(u_depths, ivec3(min(origin + ivec2(bx, by), size - 1), u_layer), 0).r;
      vec2 w = evsmWarp(kind == 0 ? d : evsmLinearDepth(d, near, far));
      sum += vec4(w.x, w.x * w.x, w.y, w.y * w.y);
    }
  o_moments = sum / float(ratio * ratio);
}
#else
layout(binding = 1) uniform sampler2DArray u_source;  // level 0 of the moments or the scratch
uniform int u_radius;       // the box kernel: 2 u_radius + 1 texels
uniform ivec2 u_direction;  // (1, 0) or (0, 1)

void main() {
  ivec2 dst = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  for (int t = -u_radius; t <= u_radius; ++t)
    sum += texelFetch(u_source, ivec3(clamp(dst + t * u_direction, ivec2(0), u_momentsSize - 1), u_layer), 0);
  o_moments = sum / float(2 * u_radius + 1);
}
#endif
