// Shadows for every lighting method: the per-frame shadow data (the
// shadow_map template's info buffer; C++ mirror in
// passes/common/include/rgraph/passes/shadow_sampling.h) and one sampling
// function per filter. Include after frame.glsl and gbuffer_read.glsl (it
// reads Surface). Defines (shadows::defines): SHADOWS, SHADOW_MAX_MAPS,
// one of SHADOW_FILTER_HARD / _PCF / _PCSS, SHADOW_PCF_SIZE. Without SHADOWS
// both visibility functions are the constant 1: no shadow code at all.
#if defined(SHADOWS)
struct ShadowMap {
  mat4 viewProj[6];  // per layer: cascade k, face k (+x -x +y -y +z -z), [0] for a spot light
  vec4 splits;       // directional: far view depth of cascades 0..3
  ivec4 layers;      // x: first atlas layer, y: layer count, z: kind (0 directional, 1 spot, 2 point)
  vec4 texel;        // directional: world units per texel of cascades 0..3; spot, point: x at distance 1
  vec4 light;        // spot, point: xyz position, w: far plane
};
layout(std430, binding = 6) readonly buffer ShadowInfo {
  ivec4 u_shadowCounts;  // x: maps, y: the directional light's map (-1: none), z: lights
  vec4 u_shadowParams;   // x: normal offset (texels), y: pcss light size (texels)
  ShadowMap shadowMaps[SHADOW_MAX_MAPS];
  int lightShadow[];     // per light of the lights buffer: its map, -1: none
};
layout(binding = 6) uniform sampler2DArrayShadow u_shadowAtlas;
// The G-buffer position's relative error (2^-11 for half floats: 0.003 units
// at 6 units from the origin, more than a texel of a sharp map), set by the
// pass from the position target's format (shadows::bindInfo): the lookup
// moves that much towards the light, so quantised positions do not shadow
// themselves.
uniform float u_shadowPositionError;
#if defined(SHADOW_FILTER_PCSS)
layout(binding = 7) uniform sampler2DArray u_shadowDepths;
#endif

// One comparison per texel of an NxN kernel `scale` texels apart; each tap
// is the hardware's bilinear 2x2 comparison (the sampler is linear).
float shadowKernel(vec2 uv, float layer, float depth, float scale) {
  vec2 texel = scale / vec2(textureSize(u_shadowAtlas, 0).xy);
  const int r = SHADOW_PCF_SIZE / 2;
  float sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) sum += texture(u_shadowAtlas, vec4(uv + vec2(x, y) * texel, layer, depth));
  return sum / float(SHADOW_PCF_SIZE * SHADOW_PCF_SIZE);
}

float filteredShadow(vec2 uv, float layer, float depth, float receiverDistance) {
#if defined(SHADOW_FILTER_HARD)
  // At a texel centre the bilinear comparison is that texel's alone.
  vec2 size = vec2(textureSize(u_shadowAtlas, 0).xy);
  return texture(u_shadowAtlas, vec4((floor(uv * size) + 0.5) / size, layer, depth));
#elif defined(SHADOW_FILTER_PCSS)
  // Blocker search over the kernel at the light's size, then a kernel as wide
  // as the penumbra a light of that size casts from the blockers' mean depth.
  vec2 texel = 1.0 / vec2(textureSize(u_shadowDepths, 0).xy);
  const int r = SHADOW_PCF_SIZE / 2;
  float lightSize = u_shadowParams.y;
  float blockers = 0.0, sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      float d = texture(u_shadowDepths, vec3(uv + vec2(x, y) * texel * max(lightSize / float(r + 1), 1.0), layer)).r;
      if (d < depth) { sum += d; blockers += 1.0; }
    }
  if (blockers == 0.0) return 1.0;
  float blocker = sum / blockers;
  float penumbra = clamp((depth - blocker) / max(blocker, 1e-4) * lightSize, 1.0, 4.0 * lightSize);
  return shadowKernel(uv, layer, depth, penumbra / float(r + 1));
#else
  return shadowKernel(uv, layer, depth, 1.0);
#endif
}

// Visibility of shadow map m from surface point P (normal N, towards the light L).
float shadowOfMap(int m, vec3 P, vec3 N, vec3 L) {
  int kind = shadowMaps[m].layers.z;
  int k = 0;
  float texel = shadowMaps[m].texel.x;
  if (kind == 0) {
    float depth = -(u_view * vec4(P, 1.0)).z;
    int count = shadowMaps[m].layers.y;
    while (k < count && depth >= shadowMaps[m].splits[k]) ++k;
    if (k == count) return 1.0;  // beyond the last cascade: unshadowed
    texel = shadowMaps[m].texel[k];
  } else {
    vec3 d = P - shadowMaps[m].light.xyz;
    float distance = length(d);
    if (kind == 2) {
      vec3 ad = abs(d);
      k = ad.x >= ad.y && ad.x >= ad.z ? (d.x >= 0.0 ? 0 : 1) : ad.y >= ad.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5);
    }
    texel *= distance;
  }
  // Normal offset: look the receiver up a few texels off its surface, so that
  // a lit surface is not shadowed by its own map's texels (acne).
  vec3 a = abs(P);
  vec3 offsetP = P + N * (u_shadowParams.x * texel) + L * (2.0 * u_shadowPositionError * max(a.x, max(a.y, a.z)));
  vec4 clip = shadowMaps[m].viewProj[k] * vec4(offsetP, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z > 1.0) return 1.0;
  return filteredShadow(ndc.xy * 0.5 + 0.5, float(shadowMaps[m].layers.x + k), ndc.z * 0.5 + 0.5,
                        length(offsetP - shadowMaps[m].light.xyz));
}

// The first directional light's visibility, and light i's (of the lights buffer).
float sunVisibility(Surface s) {
  int m = u_shadowCounts.y;
  return m < 0 ? 1.0 : shadowOfMap(m, s.position, s.normal, normalize(-u_dirLightDir.xyz));
}
float lightVisibility(int i, Surface s) {
  int m = lightShadow[i];
  return m < 0 ? 1.0 : shadowOfMap(m, s.position, s.normal, normalize(shadowMaps[m].light.xyz - s.position));
}
#else
float sunVisibility(Surface s) { return 1.0; }
float lightVisibility(int i, Surface s) { return 1.0; }
#endif
