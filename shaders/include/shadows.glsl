// Shadows for every lighting method: the per-frame shadow data (the
// shadow_map template's info buffer; C++ mirror in
// passes/common/include/rgraph/passes/shadow_sampling.h) and one sampling
// function per filter. Include after frame.glsl and gbuffer_read.glsl (it
// reads Surface). Defines (shadows::defines): SHADOWS, SHADOW_MAX_MAPS,
// one of SHADOW_FILTER_HARD / _PCF / _PCSS / _EVSM, SHADOW_PCF_SIZE,
// SHADOW_EVSM_BLEED. Without SHADOWS both visibility functions are the
// constant 1: no shadow code at all. SHADOW_INFO_ONLY (with
// SHADOW_MAX_MAPS): the ShadowInfo block and the EVSM warp alone, for the
// shadow_moments pass (which has no Surface to shade).
#if defined(SHADOWS) || defined(SHADOW_INFO_ONLY)
struct ShadowMap {
  mat4 viewProj[6];  // per layer: cascade k, face k (+x -x +y -y +z -z), [0] for a spot light
  vec4 splits;       // directional: far view depth of cascades 0..3
  ivec4 layers;      // x: first atlas layer, y: layer count, z: kind (0 directional, 1 spot, 2 point)
  vec4 texel;        // directional: world units per texel of cascades 0..3; spot, point: x at distance 1,
                     // y: the near plane
  vec4 light;        // spot, point: xyz position, w: far plane
};
layout(std430, binding = 6) readonly buffer ShadowInfo {
  ivec4 u_shadowCounts;  // x: maps, y: the directional light's map (-1: none), z: lights
  vec4 u_shadowParams;   // x: normal offset (texels), y: pcss light size (texels), zw: EVSM exponents
  ShadowMap shadowMaps[SHADOW_MAX_MAPS];
  int lightShadow[];     // per light of the lights buffer: its map, -1: none
};

// EVSM. Depth in 0..1, linear in distance (directional maps: their window
// depth; spot and point maps: the distance along the axis between the near
// and far planes), warped by exp(+c x) and -exp(-c x) with x = 2 depth - 1.
// The exponents come from the info buffer, clamped to what the moments'
// format holds (shadows::evsmMaxExponent, set by the pass).
uniform float u_evsmMaxExponent;
vec2 evsmExponents() { return min(u_shadowParams.zw, vec2(u_evsmMaxExponent)); }
vec2 evsmWarp(float depth) {
  vec2 c = evsmExponents();
  float x = 2.0 * clamp(depth, 0.0, 1.0) - 1.0;
  return vec2(exp(c.x * x), -exp(-c.y * x));
}
// A perspective map's window depth (0..1) as EVSM's linear depth.
float evsmLinearDepth(float window, float near, float far) {
  float ndc = 2.0 * window - 1.0;
  float distance = 2.0 * near * far / (far + near - ndc * (far - near));
  return (distance - near) / (far - near);
}
#endif

#if defined(SHADOWS)
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
#if defined(SHADOW_FILTER_EVSM)
layout(binding = 8) uniform sampler2DArray u_shadowMoments;

// Chebyshev's upper bound on the share of the filter region at least as far
// as `t`, from the region's mean and mean square of the warped depth.
float chebyshev(vec2 moments, float t, float minVariance) {
  if (t <= moments.x) return 1.0;
  float variance = max(moments.y - moments.x * moments.x, minVariance);
  float d = t - moments.x;
  return variance / (variance + d * d);
}

// Visibility from the moments around uv at mip `lod`: the tighter of the
// positive and negative warps' bounds, then the light-bleeding reduction
// (the bound below SHADOW_EVSM_BLEED is a leak: cut to 0, the rest rescaled).
float evsmShadow(vec2 uv, float layer, float depth, float lod) {
  vec4 m = textureLod(u_shadowMoments, vec3(uv, layer), lod);
  vec2 w = evsmWarp(depth);
  vec2 c = evsmExponents();
  // The variance floor scales with the warp's slope at the receiver (1e-4 of a depth unit).
  vec2 floorVariance = (1e-4 * c * abs(w)) * (1e-4 * c * abs(w));
  float p = min(chebyshev(m.xy, w.x, floorVariance.x), chebyshev(m.zw, w.y, floorVariance.y));
  return clamp((p - SHADOW_EVSM_BLEED) / (1.0 - SHADOW_EVSM_BLEED), 0.0, 1.0);
}
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
#if defined(SHADOW_FILTER_EVSM)
  // The mip level whose texels match the pixel's footprint on the surface:
  // a moments texel spans (atlas / moments size) map texels.
  float pixelWorld = 2.0 * -(u_view * vec4(P, 1.0)).z / (u_proj[1][1] * u_viewport.y);
  float momentTexel = texel * float(textureSize(u_shadowAtlas, 0).x) / float(textureSize(u_shadowMoments, 0).x);
  float lod = log2(max(pixelWorld / max(momentTexel, 1e-20), 1.0));
  float receiverDepth = kind == 0 ? ndc.z * 0.5 + 0.5
                           : (clip.w - shadowMaps[m].texel.y) / (shadowMaps[m].light.w - shadowMaps[m].texel.y);
  return evsmShadow(ndc.xy * 0.5 + 0.5, float(shadowMaps[m].layers.x + k), receiverDepth, lod);
#endif
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
#elif !defined(SHADOW_INFO_ONLY)
float sunVisibility(Surface s) { return 1.0; }
float lightVisibility(int i, Surface s) { return 1.0; }
#endif
