#version 450 core
// SSAO computed at a reduced size (ssao and ssao_blur into smaller targets),
// brought back to the G-buffer's size with a depth-aware (joint bilateral)
// upsample: each pixel blends the 2x2 low-resolution texels around it with
// their bilinear weights, each times exp(-(dz / (z * u_tolerance))^2), where
// dz is the view depth of the G-buffer texel that texel's ssao sample read
// (the same rounding as ssao.frag) minus this pixel's depth. A texel across a
// silhouette thus gives (almost) nothing; when all four are across one, the
// nearest in depth is taken. Defines: one GBUFFER_* (as ssao.frag).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"

layout(binding = 0) uniform sampler2D u_src;       // low-resolution ambient visibility
layout(binding = 1) uniform sampler2D g_position;  // not in compact
layout(binding = 4) uniform sampler2D g_depth;     // compact only
uniform vec2 u_gbufferSize;
uniform float u_tolerance;  // relative depth difference where a texel's weight falls to 1/e

layout(location = 0) out float outAo;

// Distance along the view axis at a G-buffer texel; negative where nothing was drawn.
float viewDepth(ivec2 px) {
#if defined(GBUFFER_COMPACT)
  float depth = texelFetch(g_depth, px, 0).r;
  if (depth >= 1.0) return -1.0;
  vec2 uv = (vec2(px) + 0.5) / u_gbufferSize;
  vec4 view = u_invProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  return -view.z / view.w;
#else
  vec4 p = texelFetch(g_position, px, 0);
  if (p.w <= 0.5) return -1.0;
  return -(u_view * vec4(p.xyz, 1.0)).z;
#endif
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  float z = viewDepth(px);
  if (z < 0.0) {
    outAo = 1.0;  // background: nothing to occlude (as ssao.frag)
    return;
  }
  vec2 low = vec2(textureSize(u_src, 0));
  vec2 scale = low / u_gbufferSize;
  vec2 s = (vec2(px) + 0.5) * scale - 0.5;  // low-resolution coordinates, texel centres at integers
  ivec2 base = ivec2(floor(s));
  vec2 f = s - vec2(base);
  float sum = 0.0, total = 0.0, nearest = 1e30, nearestAo = 1.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 t = clamp(base + ivec2(i, j), ivec2(0), ivec2(low) - 1);
      ivec2 g = clamp(ivec2((vec2(t) + 0.5) / scale), ivec2(0), ivec2(u_gbufferSize) - 1);
      float zt = viewDepth(g);
      float ao = texelFetch(u_src, t, 0).r;
      float d = zt < 0.0 ? 1e30 : abs(zt - z) / (z * u_tolerance);
      float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y) * exp(-d * d);
      sum += ao * w;
      total += w;
      if (d < nearest) nearest = d, nearestAo = ao;
    }
  outAo = total > 1e-4 ? sum / total : nearestAo;
}
