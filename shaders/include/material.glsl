// Material inputs of a scene draw (set per draw by GpuScene::drawPrimitives)
// and the surface they describe at one fragment. Defines: HAS_NORMAL_MAPS
// (only when the scene has normal maps: otherwise no tangent is read and no
// normal map sampled). Textures are sampled at materialUv(unit): their own UV
// set and KHR_texture_transform (include/material_uv.glsl, included before this file).
layout(binding = 0) uniform sampler2D u_baseColorTex;
layout(binding = 1) uniform sampler2D u_metallicRoughnessTex;
layout(binding = 2) uniform sampler2D u_normalTex;
layout(binding = 3) uniform sampler2D u_occlusionTex;
// White when the material has none (GpuScene binds a 1x1 white texture).
layout(binding = 4) uniform sampler2D u_emissiveTex;       // sRGB
layout(binding = 11) uniform sampler2D u_specularTex;      // linear, A
layout(binding = 12) uniform sampler2D u_specularColorTex;  // sRGB, RGB

uniform vec4 u_baseColorFactor;
uniform float u_metallicFactor;
uniform float u_roughnessFactor;
uniform float u_specular;
uniform float u_normalScale;
uniform float u_occlusionStrength;
uniform float u_alphaCutoff;
uniform int u_alphaMode;  // 0 opaque, 1 mask, 2 blend
uniform vec3 u_emissive;  // emissiveFactor x KHR_materials_emissive_strength
uniform vec3 u_specularColorFactor;  // KHR_materials_specular
uniform float u_specularFactor;
uniform int u_unlit;  // KHR_materials_unlit
// Bit 0: u_specularTex bound, bit 1: u_specularColorTex bound. GpuScene sets
// these three only in scenes that have KHR_materials_specular or unlit
// materials (otherwise they keep the defaults, and units 11 and 12 are not bound).
uniform int u_specularTextures;
uniform int u_hasBaseColorTex;
uniform int u_hasMetallicRoughnessTex;
uniform int u_hasNormalTex;
uniform int u_hasOcclusionTex;

in VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} fs;
in vec4 vs_color;  // COLOR_0 (white where the mesh has none): scales base colour and alpha
// Read only where the mesh has COLOR_0: a constant white interpolated across a
// triangle comes out a rounding below 1 (0.99999994), which a format that
// truncates (r11g11b10f) turns into a whole step (1/128).
uniform int u_hasVertexColors;

vec2 materialUv(int unit) { return textureUv(unit, fs.uv); }

vec4 materialBaseColor() {
  vec4 c = u_baseColorFactor;
  if (u_hasVertexColors != 0) c *= vs_color;
  if (u_hasBaseColorTex != 0) c *= texture(u_baseColorTex, materialUv(0));
  return c;
}

// Builds the surface; `discarded` is set for alpha-masked fragments below the cut-off.
Surface materialSurface(vec3 viewDir, out float alpha, out bool discarded) {
  Surface s;
  vec4 base = materialBaseColor();
  alpha = base.a;
  discarded = (u_alphaMode == 1 && base.a < u_alphaCutoff);
  s.position = fs.worldPos;
  s.albedo = base.rgb;
  s.specular = u_specular;
  vec2 mr = vec2(u_metallicFactor, u_roughnessFactor);
  if (u_hasMetallicRoughnessTex != 0) {
    vec4 t = texture(u_metallicRoughnessTex, materialUv(1));
    mr *= vec2(t.b, t.g);
  }
  s.metallic = clamp(mr.x, 0.0, 1.0);
  s.roughness = clamp(mr.y, 0.04, 1.0);
  s.ao = 1.0;
  if (u_hasOcclusionTex != 0) s.ao = 1.0 + u_occlusionStrength * (texture(u_occlusionTex, materialUv(3)).r - 1.0);

  vec3 N = safeNormal(fs.normal, viewDir);
  if (!gl_FrontFacing) N = -N;  // double-sided materials seen from behind
#if defined(HAS_NORMAL_MAPS)
  if (u_hasNormalTex != 0 && dot(fs.tangent.xyz, fs.tangent.xyz) > 1e-12) {
    vec3 T = normalize(fs.tangent.xyz - N * dot(N, fs.tangent.xyz));
    vec3 B = (gl_FrontFacing ? 1.0 : -1.0) * fs.tangent.w * cross(N, T);
    vec3 tn = texture(u_normalTex, materialUv(2)).xyz * 2.0 - 1.0;
    tn.xy *= u_normalScale;
    N = safeNormal(mat3(T, B, N) * tn, N);
  }
#endif
  s.normal = N;
  s.emissive = u_emissive * texture(u_emissiveTex, materialUv(4)).rgb;
  // KHR_materials_specular's dielectric F0 and F90 (lighting.glsl's surfaceF0
  // and surfaceF90 mix in the metals).
  float specularA = (u_specularTextures & 1) != 0 ? texture(u_specularTex, materialUv(11)).a : 1.0;
  vec3 specularRgb = (u_specularTextures & 2) != 0 ? texture(u_specularColorTex, materialUv(12)).rgb : vec3(1.0);
  s.f90 = u_specularFactor * specularA;
  s.f0 = min(vec3(0.04) * u_specularColorFactor * specularRgb, vec3(1.0)) * s.f90;
  if (u_unlit != 0) {
    // Unlit: the base colour (with whatever materialBaseColor multiplies in,
    // vertex colours included) is all the pixel shows. It goes out as light
    // of its own; nothing reflects, so every lighting method adds exactly it.
    s.emissive = base.rgb;
    s.albedo = vec3(0.0);
    s.specular = 0.0;
    s.metallic = 0.0;
    s.f0 = vec3(0.0);
    s.f90 = 0.0;
  }
  s.covered = true;
  return s;
}
