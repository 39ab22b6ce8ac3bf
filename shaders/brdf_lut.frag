#version 450 core
// passes/brdf_lut: the split-sum's second factor (Karis 2013): for n.v along
// x and roughness along y (texel centres), the scale A and bias B of F0 in
// the GGX + Smith (k = alpha / 2) specular albedo, integrated with GGX
// importance sampling: specular albedo = F0 * A + B.
#include "include/ibl.glsl"

in vec2 v_uv;
layout(location = 0) out vec2 outColor;

const uint SAMPLES = 2048u;

float smithIbl(float NdotV, float NdotL, float roughness) {
  float k = roughness * roughness / 2.0;
  return (NdotV / (NdotV * (1.0 - k) + k)) * (NdotL / (NdotL * (1.0 - k) + k));
}

void main() {
  float NdotV = max(v_uv.x, 1e-3);
  float roughness = v_uv.y;
  vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
  vec3 N = vec3(0.0, 0.0, 1.0);
  float A = 0.0, B = 0.0;
  for (uint i = 0u; i < SAMPLES; ++i) {
    vec3 H = importanceSampleGGX(hammersley(i, SAMPLES), N, roughness);
    vec3 L = 2.0 * dot(V, H) * H - V;
    float NdotL = L.z;
    if (NdotL <= 0.0) continue;
    float NdotH = max(H.z, 0.0);
    float VdotH = max(dot(V, H), 0.0);
    float visibility = smithIbl(NdotV, NdotL, roughness) * VdotH / max(NdotH * NdotV, 1e-6);
    float Fc = pow(1.0 - VdotH, 5.0);
    A += (1.0 - Fc) * visibility;
    B += Fc * visibility;
  }
  outColor = vec2(A, B) / float(SAMPLES);
}
