#version 450 core
// Temporal anti-aliasing resolve (after the published ideas of Karis 2014,
// "High quality temporal supersampling", and Salvi's variance clipping):
//  - velocity dilation: the motion of the nearest surface in the 3x3 block,
//    so that edges of moving objects reproject with the object, not with
//    the background behind them; where the velocity input holds exactly 0
//    (the background), or where something drawn after it without motion
//    vectors is in front of the surface it was written for (a forward pass's
//    light boxes: depth nearer than velocity_depth, when that is bound), the
//    camera's motion reprojected from depth (an object moving exactly with
//    the camera would be taken for static there);
//  - the current frame at the unjittered pixel centre where the pixel moves
//    (a Gaussian over the 3x3, each sample at its jittered position): in
//    motion the current frame carries ~40% of the result, and its jitter
//    would show as a sub-pixel wobble (docs/performance.md);
//  - reprojection: the history at uv - velocity (Catmull-Rom, so that the
//    image does not soften a little more every frame it moves);
//  - rejection: history from outside the screen is dropped; history outside
//    the neighbourhood of the current frame is clipped towards its mean in
//    YCoCg, inside the box mean +- gamma * sigma of the 3x3 (intersected with
//    its min/max), and when it was far outside (disocclusion, a change of
//    lighting) it gets no weight at all;
//  - blend: a running mean while the pixel's history is young (n frames:
//    weight n / (n + 1)), then u_historyWeight, or u_motionHistoryWeight
//    where the pixel moves: every reprojection resamples and clips the
//    history, so in motion a shorter one is closer to the supersampled image
//    (docs/performance.md measures it). Linear in light up to luma 1, what
//    the display shows after a clamping tone map; above it, Karis'
//    inverse-luma weights, so that a single HDR highlight does not flicker
//    (applied below 1 too they darkened every edge between bright and dark);
//  - still pixels: the clip box is built from this frame's 3x3 alone, so a
//    sub-pixel wire that the current jitter phase misses would be clipped
//    out of the history every such frame and never accumulate. Alpha keeps,
//    per pixel, how many frames in a row it was still (no motion, history
//    accepted) and the history's age (packCounters); once a pixel has been
//    still kStillFrames frames its history is neither clipped nor rejected, so it converges
//    to the average of every jitter phase. Motion resets the count, so trails
//    and disocclusions are clipped as before (their pixels moved); a change
//    of lighting on a still scene fades in over ~1 / (1 - weight) frames;
//  - robustness: NaN/Inf read from the history or the current frame become
//    zero before they are used, and what is written is always finite, so a
//    bad value never survives a frame.
#include "include/frame.glsl"

in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_color;
layout(binding = 1) uniform sampler2D u_history;
layout(binding = 2) uniform sampler2D u_velocity;
layout(binding = 3) uniform sampler2D u_depth;
layout(binding = 4) uniform sampler2D u_velocityDepth;  // bound when u_hasVelocityDepth == 1
uniform int u_hasVelocityDepth;
uniform int u_historyValid;      // 0: the history is cleared (first frame, resize, cut): output the current frame
uniform float u_historyWeight;   // share of the history in the blend (0.9: ~10 frames to converge)
uniform float u_motionHistoryWeight;  // the same where the pixel moves (each reprojection resamples it)
uniform float u_clipGamma;       // width of the variance box in standard deviations
uniform float u_rejectDistance;  // history farther than this many box sizes outside: disoccluded, dropped
uniform float u_sharpen;         // unsharp mask on the current frame before the blend (0 off)
uniform float u_currentFilter;   // sigma (pixels) of the unjittered reconstruction of the current frame (0 off)
layout(location = 0) out vec4 outColor;

// Frames a pixel must stay still before its history is trusted unclipped:
// the jitter phases of deferred-taa.json, so that every phase was seen once.
const float kStillFrames = 8.0;
// Frames of history counted per pixel (its age): a history of n frames gets
// the weight n / (n + 1) until that reaches u_historyWeight, a running mean,
// so that a pixel whose history is young (the first frames, a disocclusion)
// converges in a few frames instead of keeping the aliased frame it started
// from for ~1 / (1 - weight) frames.
const float kMaxAge = 15.0;

// The history's alpha packs both counters (still frames, age) as an integer:
// exact in rgba16f, and read without filtering at the reprojected texel.
float packCounters(float stillFrames, float age) { return stillFrames * (kMaxAge + 1.0) + age; }
void unpackCounters(float stored, out float stillFrames, out float age) {
  if (isnan(stored) || isinf(stored) || stored < 0.0) stored = 0.0;
  float still = floor(stored / (kMaxAge + 1.0));
  age = clamp(stored - still * (kMaxAge + 1.0), 0.0, kMaxAge);
  stillFrames = min(still, kStillFrames);
}

vec3 finite(vec3 c) {
  return mix(c, vec3(0.0), bvec3(isnan(c.r) || isinf(c.r), isnan(c.g) || isinf(c.g), isnan(c.b) || isinf(c.b)));
}
vec3 toYCoCg(vec3 c) {
  return vec3(dot(c, vec3(0.25, 0.5, 0.25)), dot(c, vec3(0.5, 0.0, -0.5)), dot(c, vec3(-0.25, 0.5, -0.25)));
}
vec3 fromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// The history at `uv` through a Catmull-Rom filter: bilinear taps would
// blur the image a little more every frame it is reprojected by a fraction
// of a pixel. The 4x4 cubic weights per axis fold into 3 bilinear taps (the
// middle two texels share one tap at their weighted position): 9 taps.
// `finiteTaps` is false when a tap that counts read NaN/Inf (a tap of zero
// weight, the outer ones of a whole-pixel shift, is skipped: 0 * NaN is NaN).
vec3 historyCatmullRom(vec2 uv, out bool finiteTaps) {
  vec2 size = vec2(textureSize(u_history, 0));
  vec2 pos = uv * size - 0.5;
  vec2 base = floor(pos);
  vec2 f = pos - base;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 t0 = (base - 0.5) / size, t12 = (base + 0.5 + w2 / w12) / size, t3 = (base + 2.5) / size;
  vec2 tx[3] = vec2[](t0, t12, t3), wx[3] = vec2[](w0, w12, w3);
  vec3 sum = vec3(0.0);
  finiteTaps = true;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      float w = wx[i].x * wx[j].y;
      if (w == 0.0) continue;
      vec3 c = textureLod(u_history, vec2(tx[i].x, tx[j].y), 0.0).rgb;
      if (any(isnan(c)) || any(isinf(c)) || any(greaterThan(abs(c), vec3(65504.0)))) finiteTaps = false;
      sum += finite(c) * w;
    }
  return sum;
}

// The motion of a static point seen at pixel p with depth d: where the
// previous camera saw it. For what the velocity input does not cover (a
// forward pass that writes no motion vectors, the background). The depth
// was rendered with this frame's jitter, so the jittered inverse undoes it.
vec2 cameraVelocity(ivec2 p, float d) {
  vec2 ndc = (vec2(p) + 0.5) * u_viewport.zw * 2.0 - 1.0;
  vec4 view = u_invProj * vec4(ndc, d * 2.0 - 1.0, 1.0);
  vec4 world = u_invView * vec4(view.xyz / view.w, 1.0);
  vec4 now = u_viewProjNoJitter * world, before = u_prevViewProj * world;
  if (now.w <= 0.0 || before.w <= 0.0) return vec2(0.0);
  return 0.5 * (now.xy / now.w - before.xy / before.w);
}

vec3 currentAt(ivec2 p) {
  ivec2 size = textureSize(u_color, 0);
  return max(finite(texelFetch(u_color, clamp(p, ivec2(0), size - 1), 0).rgb), vec3(0.0));
}

// This frame's colour at the unjittered centre of pixel p: pixel q sampled
// the scene at q + 0.5 - jitter, so each of the 3x3 is weighed by its
// sample's distance to p + 0.5 (a Gaussian of sigma u_currentFilter).
// Without jitter (u_frame.y == 0) or with the filter off: the centre sample.
vec3 currentUnjittered(ivec2 p, vec3 center) {
  if (u_currentFilter <= 0.0 || u_frame.y == 0) return center;
  vec3 acc = vec3(0.0);
  float wsum = 0.0;
  float k = -0.5 / (u_currentFilter * u_currentFilter);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      vec2 d = vec2(x, y) - u_jitter.xy;
      float w = exp(k * dot(d, d));
      acc += currentAt(p + ivec2(x, y)) * w;
      wsum += w;
    }
  return acc / wsum;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_color, 0);
  vec3 center = currentAt(p);

  // 3x3 statistics in YCoCg, the nearest depth, the cross for sharpening.
  vec3 lo = vec3(1e30), hi = vec3(-1e30), sum = vec3(0.0), sum2 = vec3(0.0), cross = vec3(0.0);
  float nearest = 2.0;
  ivec2 nearestP = p;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(p + ivec2(x, y), ivec2(0), size - 1);
      vec3 c = currentAt(q);
      if (abs(x) + abs(y) == 1) cross += c;
      vec3 ycc = toYCoCg(c);
      lo = min(lo, ycc);
      hi = max(hi, ycc);
      sum += ycc;
      sum2 += ycc * ycc;
      float d = texelFetch(u_depth, q, 0).r;
      if (d < nearest) {
        nearest = d;
        nearestP = q;
      }
    }
  }

  vec2 velocity = texelFetch(u_velocity, nearestP, 0).rg;
  if (any(isnan(velocity)) || any(isinf(velocity))) velocity = vec2(0.0);
  // Something drawn after the velocity input (without motion vectors) is in
  // front of the surface whose motion it holds: not this pixel's motion.
  if (u_hasVelocityDepth == 1 && nearest < texelFetch(u_velocityDepth, nearestP, 0).r) velocity = vec2(0.0);
  // Exactly zero: nothing wrote motion there (or nothing moved): the camera's
  // motion at that depth (zero too when neither camera nor object moved).
  if (velocity == vec2(0.0)) velocity = cameraVelocity(nearestP, nearest);
  vec2 uv = (vec2(p) + 0.5) / vec2(size);
  vec2 prevUv = uv - velocity;
  bool onScreen = all(greaterThanEqual(prevUv, vec2(0.0))) && all(lessThanEqual(prevUv, vec2(1.0)));
  // Still: no motion at all (the motion vectors are unjittered, so a jittered
  // still camera gives exactly 0).
  bool still = all(lessThan(abs(velocity * vec2(size)), vec2(1e-3)));
  // Where the pixel moves the history weighs less (u_motionHistoryWeight)
  // and is clipped, so the current frame's jitter would show as a sub-pixel
  // wobble: it is taken at the unjittered centre. A still pixel keeps its raw
  // sample, which its history averages over every jitter phase (filtered, a
  // sub-pixel wire would be smeared into its neighbours every frame its
  // young history is rejected), and so does a first frame (still: no motion).
  bool noHistory = u_historyValid == 0 || !onScreen;
  vec3 current = still ? center : currentUnjittered(p, center);
  if (u_sharpen > 0.0) current = max(current + u_sharpen * (current - 0.25 * cross), vec3(0.0));
  if (noHistory) {
    outColor = vec4(current, packCounters(0.0, 1.0));
    return;
  }
  float stillFrames, age;
  ivec2 historyTexel = clamp(ivec2(floor(prevUv * vec2(size))), ivec2(0), size - 1);
  unpackCounters(texelFetch(u_history, historyTexel, 0).a, stillFrames, age);
  bool trusted = still && stillFrames >= kStillFrames;
  // Counted whether or not the history is used this frame: a wire pixel whose
  // history is rejected while it is still young must still come of age.
  float nextStill = still ? min(stillFrames + 1.0, kStillFrames) : 0.0;

  // History that read NaN/Inf is garbage: dropped for this pixel (weight 0
  // below) rather than clipped.
  bool historyFinite;
  vec3 raw = historyCatmullRom(prevUv, historyFinite);
  vec3 history = toYCoCg(max(finite(raw), vec3(0.0)));
  vec3 mean = sum / 9.0;
  vec3 sigma = sqrt(max(sum2 / 9.0 - mean * mean, vec3(0.0)));
  vec3 boxLo = max(lo, mean - u_clipGamma * sigma), boxHi = min(hi, mean + u_clipGamma * sigma);
  vec3 boxCenter = 0.5 * (boxLo + boxHi), extent = max(0.5 * (boxHi - boxLo), vec3(1e-4));
  // Clip the history along the line to the box centre (keeps its chroma
  // direction, unlike a per-channel clamp); t > 1: it was outside.
  vec3 offset = history - boxCenter;
  vec3 units = abs(offset / extent);
  float t = max(units.x, max(units.y, units.z));
  vec3 clipped = t > 1.0 && !trusted ? boxCenter + offset / t : history;

  float weight = min(still ? u_historyWeight : u_motionHistoryWeight, age / (age + 1.0));
  // Far outside the box: a surface the history never saw (disocclusion).
  if ((t > 1.0 + u_rejectDistance && !trusted) || !historyFinite) weight = 0.0;
  if (weight <= 0.0) {
    outColor = vec4(current, packCounters(nextStill, 1.0));  // the current frame alone
    return;
  }
  vec3 cur = current;
  vec3 his = max(fromYCoCg(clipped), vec3(0.0));
  // Linear up to luma 1; inverse-luma weights above (see the top).
  float wc = (1.0 - weight) / (1.0 + max(toYCoCg(cur).x - 1.0, 0.0));
  float wh = weight / (1.0 + max(toYCoCg(his).x - 1.0, 0.0));
  vec3 result = (cur * wc + his * wh) / max(wc + wh, 1e-6);
  outColor = vec4(finite(result), packCounters(nextStill, min(age + 1.0, kMaxAge)));
}
