#version 450 core
// passes/specular_cube: one level of the split-sum's pre-filtered radiance
// (Karis 2013, with N = V = R): GGX-importance-sampled light directions
// around the texel's direction, weighted by n.l, each read from the
// environment level whose texel covers the sample's solid angle (filtered
// importance sampling, Colbert and Krivanek 2007), so that few samples do.
#include "include/ibl.glsl"

uniform int u_face;
uniform float u_roughness;
uniform float u_sourceSize;   // the environment cube's level-0 width
uniform float u_sourceLevels; // its level count
layout(binding = 0) uniform samplerCube u_environment;

in vec2 v_uv;
layout(location = 0) out vec4 outColor;

const uint SAMPLES = 512u;

void main() {
  vec3 N = cubeFaceDirection(u_face, v_uv);
  if (u_roughness <= 0.0) {
    outColor = vec4(textureLod(u_environment, N, 0.0).rgb, 1.0);
    return;
  }
  float texelSolidAngle = 4.0 * IBL_PI / (6.0 * u_sourceSize * u_sourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (uint i = 0u; i < SAMPLES; ++i) {
    vec3 H = importanceSampleGGX(hammersley(i, SAMPLES), N, u_roughness);
    vec3 L = 2.0 * dot(N, H) * H - N;
    float NdotL = dot(N, L);
    if (NdotL <= 0.0) continue;
    float NdotH = max(dot(N, H), 0.0);
    // pdf of L with N = V: D(h) (n.h) / (4 (v.h)) = D(h) / 4
    float pdf = iblDistributionGGX(NdotH, u_roughness) * 0.25 + 1e-4;
    float sampleSolidAngle = 1.0 / (float(SAMPLES) * pdf);
    float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle), 0.0, u_sourceLevels - 1.0);
    sum += textureLod(u_environment, L, lod).rgb * NdotL;
    weight += NdotL;
  }
  outColor = vec4(sum / max(weight, 1e-6), 1.0);
}
