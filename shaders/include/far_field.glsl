// The far field of the lights a tile does not list (FAR_FIELD): their
// attenuation past the cut-off radius is small and smooth, but summed over
// many lights it is most of what the cut-off loses. Each such light's
// unwindowed radiance at one point of the tile (or of its quarter) is folded
// into 16 direction bins (above or below that point, times eight 45-degree
// sectors about the y axis: 8 octants were 2.8 dB worse in the many-lights
// scene): per bin the summed radiance (rgb), the radiance-weighted sums of
// the unit directions and of the offsets to the lights, and the gradient of
// the radiance. A pixel shades each bin as one light (diffuse and specular:
// the far lights' specular is ~2 dB of PSNR in the many-lights scene) at the
// bin's mean light position (farFieldMeanLight), so that a pixel above or
// below the summing point sees the bin's lights higher or lower (the far
// lights lie near the horizon of the floor and of the objects' tops, where
// N.L changes sign with height), its radiance scaled by the gradient and by
// the length of the mean direction (1 when the bin's lights agree in
// direction), so that the diffuse term is close to exact wherever no light of
// a bin is behind the surface.
// Why not L1 spherical harmonics: the far lights of a flat field arrive near
// the horizon, and L1's constant term lights an upward floor with a quarter
// of their radiance where the true irradiance is almost zero.
// Sums go through shared memory as 2^-20 fixed point (GL 4.5 has no float
// atomics): a tile's far field stays far below 2,048.
// Only compute shaders (FAR_FIELD_CUBES sets in shared memory) sum it.
// Needs frame.glsl and lighting.glsl first.

const float kFarFieldScale = 1048576.0;  // 2^20
#define FAR_FIELD_BINS 16
#define FAR_FIELD_SUMS 64     // FAR_FIELD_BINS x (radiance rgb, weighted direction, gradient, weighted offset)
#define FAR_FIELD_VALUES 192  // FAR_FIELD_SUMS x 3

// A light's full (unwindowed) classic attenuation: the listed lights are
// shaded with it under FAR_FIELD, so that no light's tail is lost.
PointLight farFieldUncut(PointLight light) {
  light.positionRadius.w = -1.0;
  return light;
}

// How much a bin's sums (radiance, gradient of its mean) grow `offset` away
// from where they were summed: to first order, clamped (the sums are
// smooth, not linear).
float farFieldScaleAt(vec3 radiance, vec3 gradient, vec3 offset) {
  const float w = dot(radiance, vec3(1.0 / 3.0));
  return w > 0.0 ? clamp(1.0 + dot(gradient, offset) / w, 0.25, 4.0) : 1.0;
}

int farFieldFixed(float v) { return int(round(v * kFarFieldScale)); }
float farFieldFloat(int v) { return float(v) / kFarFieldScale; }

// A bin's lights as one: the point along their mean direction (weighted sum
// of directions `dir`) at their mean distance (|weighted offsets| / |dir|),
// relative to where they were summed. At that point it lights along the mean
// direction, which makes the diffuse term exact where no light of the bin is
// behind the surface; elsewhere its parallax follows the pixel.
vec3 farFieldMeanLight(vec3 dir, vec3 offsets) {
  const float len = length(dir);
  return len > 1e-12 ? dir * (length(offsets) / (len * len)) : vec3(0.0);
}

// A set's direction bin (farFieldAdd's sums v) summed at one point, seen
// from `offset` away to first order: its mean light's direction and
// distance change, its radiance follows the gradient (tiled_deferred.comp
// moves its bin's set to a tile, clustered_far.comp to a cluster).
void farFieldMove(inout vec3 v[4], vec3 offset) {
  const vec3 mean = farFieldMeanLight(v[1], v[3]) - offset;
  const float scale = farFieldScaleAt(v[0], v[2], offset), distance = length(mean);
  const vec3 dir = distance > 1e-12 ? mean * (length(v[1]) * scale / distance) : vec3(0.0);
  v[0] *= scale;
  v[1] = dir;
  v[3] = dir * distance;
}

// One bin's light at a surface: `radiance` times `scale` from the bin's mean
// light at `toLight` (surface to light), also scaled by the length of the
// weighted direction sum `dir` over the weight (1 when the bin's lights agree
// in direction).
vec3 farFieldShadeBin(vec3 radiance, float scale, vec3 dir, vec3 toLight, Surface s, vec3 V) {
  const float weight = dot(radiance, vec3(1.0 / 3.0));
  const float len = length(dir), toMean = length(toLight);
  if (weight <= 0.0 || len <= 1e-9 || toMean <= 1e-9) return vec3(0.0);
  const vec3 L = toLight / toMean, scaled = radiance * (scale * min(len / weight, 1.0));
#if defined(LIGHTING_COOK_TORRANCE)
  return shade(s.normal, V, L, scaled, s);
#else
  // blinnPhong, with x^16 as four squarings (pow is exp2(log2) on CPUs).
  const float x = max(dot(s.normal, halfVector(L, V, s.normal)), 0.0), x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  return (max(dot(s.normal, L), 0.0) * s.albedo + (x8 * x8) * s.specular) * scaled;
#endif
}

#if defined(FAR_FIELD_CUBES)
// FAR_FIELD_CUBES sets of bins in shared memory (compute shaders).
shared int s_farSums[FAR_FIELD_CUBES][FAR_FIELD_VALUES];

void farFieldClear(uint local, uint groupSize) {
  for (uint i = local; i < uint(FAR_FIELD_CUBES * FAR_FIELD_VALUES); i += groupSize)
    s_farSums[i / uint(FAR_FIELD_VALUES)][i % uint(FAR_FIELD_VALUES)] = 0;
}

// Adds the sums v of direction bin b to shared set `set`.
void farFieldAddSums(int set, int b, vec3 v[4]) {
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c) atomicAdd(s_farSums[set][(4 * b + j) * 3 + c], farFieldFixed(v[j][c]));
}

// Adds `light`'s radiance at point p to its bin of shared set `set` (bin b:
// radiance in sums 4b, the directions weighted by the radiance's mean w in
// 4b+1, the gradient of w with respect to p in 4b+2: pixels away from p
// scale the bin by it, so that the far field is continuous from tile to tile
// instead of constant per tile; the offsets light - p weighted by w in 4b+3).
// Straight into shared memory: a private copy of the sums per invocation
// costs more on SIMD CPUs (llvmpipe spills it, or selects every bin for every
// light) than a dozen atomics per light.
void farFieldAdd(int set, PointLight light, vec3 p) {
  const vec3 toLight = light.positionRadius.xyz - p;
  const float d2 = dot(toLight, toLight);
  if (d2 < 1e-12) return;
  const float d = sqrt(d2);
  const vec3 k = light.attenuation.xyz;
  const float att = 1.0 / max(k.x + k.y * d + k.z * d2, 1e-6);
  const vec3 L = toLight / d;
  // A spot light's cone at p (include/lighting.glsl): none outside it.
  const vec3 radiance = light.color.rgb * (att * spotCone(light, L));
  // Above or below, then one of eight 45-degree sectors about the y axis.
  const int bin = (L.x >= 0.0 ? 1 : 0) + (L.z >= 0.0 ? 2 : 0) + (abs(L.x) >= abs(L.z) ? 4 : 0) + (L.y >= 0.0 ? 8 : 0);
  const float w = dot(radiance, vec3(1.0 / 3.0));
  // d att / d p = att^2 (linear + 2 quadratic d) L: nearer the light, brighter.
  farFieldAddSums(set, bin, vec3[4](radiance, L * w, L * (w * att * (k.y + 2.0 * k.z * d)), toLight * w));
}

// Bin b of shared set `set` as floats: radiance, weighted direction,
// gradient of the weight, weighted offsets (farFieldAdd's sums).
void farFieldLoad(int set, int b, out vec3 v[4]) {
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c) v[j][c] = farFieldFloat(s_farSums[set][(4 * b + j) * 3 + c]);
}
#endif
