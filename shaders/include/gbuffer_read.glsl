// Reading a G-buffer back into a Surface, for every pass that lights from it.
// Needs frame.glsl and gbuffer.glsl first, and one GBUFFER_* define.
// Texture units: 0 position, 1 normal, 2 albedo, 3 material, 4 depth,
// 9 emissive, 10 reflectance (5..8: the lighting passes' own).
layout(binding = 0) uniform sampler2D g_position;
layout(binding = 1) uniform sampler2D g_normal;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D g_material;
layout(binding = 4) uniform sampler2D g_depth;
layout(binding = 9) uniform sampler2D g_emissive;
layout(binding = 10) uniform sampler2D g_reflectance;

// Exact texel reads (texelFetch: no filtering, the G-buffer is per pixel).
Surface readSurface(ivec2 px) {
  Surface s;
  vec4 albedo = texelFetch(g_albedo, px, 0);
  s.albedo = albedo.rgb;
  s.specular = albedo.a;
  s.ao = 1.0;
  // The optional targets; without them, what no material of the scene changes.
#if defined(HAS_EMISSIVE_TARGET)
  s.emissive = texelFetch(g_emissive, px, 0).rgb;
#else
  s.emissive = vec3(0.0);
#endif
#if defined(HAS_REFLECTANCE_TARGET)
  vec4 reflectance = texelFetch(g_reflectance, px, 0);
  s.f0 = reflectance.rgb;
  s.f90 = reflectance.a;
#else
  s.f0 = vec3(0.04);
  s.f90 = 1.0;
#endif
#if defined(GBUFFER_COMPACT)
  float depth = texelFetch(g_depth, px, 0).r;
  s.covered = depth < 1.0;
  vec2 uv = (vec2(px) + 0.5) * u_viewport.zw;
  s.position = positionFromDepth(uv, depth, u_invProj, u_invView);
  s.normal = decodeOctahedral(texelFetch(g_normal, px, 0).rg);
#if defined(CONSTANT_MATERIAL)
  s.metallic = CONSTANT_METALLIC;
  s.roughness = max(CONSTANT_ROUGHNESS, 0.04);
#else
  vec2 mr = texelFetch(g_material, px, 0).rg;
  s.metallic = mr.x;
  s.roughness = max(mr.y, 0.04);
#endif
#else
  vec4 n = texelFetch(g_normal, px, 0);
  s.covered = n.w > 0.5;
  s.position = texelFetch(g_position, px, 0).xyz;
  s.normal = safeNormal(n.xyz, vec3(0.0, 0.0, 1.0));
#if defined(GBUFFER_LEARNOPENGL)
  s.metallic = 0.0;
  s.roughness = 1.0;
#elif defined(CONSTANT_MATERIAL)
  // One metallic/roughness for the whole scene: no target carries it.
  s.metallic = CONSTANT_METALLIC;
  s.roughness = max(CONSTANT_ROUGHNESS, 0.04);
#else
  vec4 m = texelFetch(g_material, px, 0);
  s.metallic = m.r;
  s.roughness = max(m.g, 0.04);
  s.ao = m.b;
#endif
#endif
  return s;
}
