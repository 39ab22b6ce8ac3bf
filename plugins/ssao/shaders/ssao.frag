#version 450 core
// Screen-space ambient occlusion with a normal-oriented hemisphere kernel
// (LearnOpenGL's SSAO chapter), from a G-buffer of any layout: the view-space
// position comes from the position target, or in the compact layout from
// depth; the normal from the normal target (octahedral in compact). A 4x4
// tile of random rotations turns the kernel per pixel; ssao_blur removes the
// resulting pattern. Writes the ambient visibility: 1 open, 0 occluded.
// Defines: one GBUFFER_* (as the lighting passes).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"

layout(binding = 0) uniform sampler2D g_position;  // not in compact
layout(binding = 1) uniform sampler2D g_normal;
layout(binding = 4) uniform sampler2D g_depth;     // compact only
layout(binding = 5) uniform sampler2D u_noise;     // 4x4 rotation vectors (xy)

const int kMaxKernel = 64;
uniform vec3 u_kernel[kMaxKernel];  // tangent-space hemisphere samples, denser near the origin
uniform int u_kernelSize;
uniform float u_radius;             // world (and view) units
uniform float u_bias;
uniform float u_power;
uniform vec2 u_gbufferSize;         // G-buffer texels (the AO target may be smaller)
uniform vec2 u_targetTexel;         // 1 / AO target size

layout(location = 0) out float outAo;

// View-space position at a G-buffer texel; false where nothing was drawn.
bool viewPosition(ivec2 px, out vec3 p) {
#if defined(GBUFFER_COMPACT)
  float depth = texelFetch(g_depth, px, 0).r;
  if (depth >= 1.0) return false;
  vec2 uv = (vec2(px) + 0.5) / u_gbufferSize;
  vec4 view = u_invProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  p = view.xyz / view.w;
#else
  if (texelFetch(g_normal, px, 0).w <= 0.5) return false;
  p = (u_view * vec4(texelFetch(g_position, px, 0).xyz, 1.0)).xyz;
#endif
  return true;
}

vec3 worldNormal(ivec2 px) {
#if defined(GBUFFER_COMPACT)
  return decodeOctahedral(texelFetch(g_normal, px, 0).rg);
#else
  return safeNormal(texelFetch(g_normal, px, 0).xyz, vec3(0.0, 0.0, 1.0));
#endif
}

void main() {
  ivec2 size = ivec2(u_gbufferSize);
  ivec2 px = clamp(ivec2(gl_FragCoord.xy * u_targetTexel * u_gbufferSize), ivec2(0), size - 1);
  vec3 P;
  if (!viewPosition(px, P)) {
    outAo = 1.0;
    return;
  }
  vec3 N = safeNormal(mat3(u_view) * worldNormal(px), vec3(0.0, 0.0, 1.0));
  vec3 rotation = vec3(texelFetch(u_noise, ivec2(gl_FragCoord.xy) & 3, 0).xy, 0.0);
  vec3 T = rotation - N * dot(rotation, N);
  T = dot(T, T) > 1e-8 ? normalize(T) : normalize(abs(N.x) < 0.9 ? cross(N, vec3(1, 0, 0)) : cross(N, vec3(0, 1, 0)));
  mat3 TBN = mat3(T, cross(N, T), N);

  float occlusion = 0.0;
  int n = clamp(u_kernelSize, 1, kMaxKernel);
  for (int i = 0; i < n; ++i) {
    vec3 s = P + TBN * u_kernel[i] * u_radius;
    vec4 clip = u_proj * vec4(s, 1.0);
    if (clip.w <= 0.0) continue;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
    vec3 scene;
    if (!viewPosition(ivec2(uv * u_gbufferSize), scene)) continue;  // background occludes nothing
    // Occluded when the surface there is in front of the sample; geometry far
    // in front (another object's silhouette) fades out over the radius.
    float range = smoothstep(0.0, 1.0, u_radius / max(abs(P.z - scene.z), 1e-4));
    occlusion += (scene.z >= s.z + u_bias ? 1.0 : 0.0) * range;
  }
  outAo = pow(clamp(1.0 - occlusion / float(n), 0.0, 1.0), u_power);
}
