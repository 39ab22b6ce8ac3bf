#version 450 core
// Shadow maps (shadow_map): depth only, no colour output. Alpha-masked
// materials cut their holes here too, so a masked fence casts a fence
// (vertex colours' alpha and the texture's UV transform included).
#include "include/material_uv.glsl"
layout(binding = 0) uniform sampler2D u_baseColorTex;
uniform vec4 u_baseColorFactor;
uniform float u_alphaCutoff;
uniform int u_alphaMode;  // 0 opaque, 1 mask, 2 blend
uniform int u_hasBaseColorTex;

in VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} fs;
in vec4 vs_color;
uniform int u_hasVertexColors;  // vs_color holds COLOR_0 (include/material.glsl says why it is asked)

void main() {
  if (u_alphaMode != 1) return;
  float alpha = u_baseColorFactor.a * (u_hasVertexColors != 0 ? vs_color.a : 1.0);
  if (u_hasBaseColorTex != 0) alpha *= texture(u_baseColorTex, textureUv(0, fs.uv)).a;
  if (alpha < u_alphaCutoff) discard;
}
