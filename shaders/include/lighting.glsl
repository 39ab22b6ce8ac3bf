// Lighting models, attenuation and spot cones shared by the deferred,
// light-volume, tiled, clustered and forward passes, so that they agree to the last bit of the maths.
// The including pass defines LIGHTING_BLINN_PHONG or LIGHTING_COOK_TORRANCE,
// and ATTENUATION_CLASSIC or ATTENUATION_SMOOTH.

const float PI = 3.14159265359;

// The half vector; L = -V (light exactly behind the surface point as seen
// from the eye) has none, and normalize(0) would be NaN.
vec3 halfVector(vec3 L, vec3 V, vec3 N) {
  vec3 h = L + V;
  return dot(h, h) > 1e-12 ? normalize(h) : N;
}

// Classic: 1 / (kc + kl d + kq d^2), cut off at the light's radius (a negative
// radius means no cut-off; a zero radius lights nothing). Smooth:
// max(1 - (d/r)^2, 0), reaching zero at r.
float attenuate(PointLight light, float d) {
  float radius = light.positionRadius.w;
#if defined(ATTENUATION_SMOOTH)
  float x = d / max(radius, 1e-6);
  return radius > 0.0 ? max(1.0 - x * x, 0.0) : 0.0;
#else
  vec3 k = light.attenuation.xyz;
  float a = 1.0 / max(k.x + k.y * d + k.z * d * d, 1e-6);
  return (radius < 0.0 || d <= radius) ? a : 0.0;  // a select, not a branch
#endif
}

// A spot light's cone, as glTF KHR_lights_punctual defines it: with cd the
// cosine of the angle between the cone's axis and the direction from the
// light to the surface, clamp((cd - cos(outer)) / (cos(inner) - cos(outer)), 0, 1)
// squared (the denominator at least 1e-3): 1 within the inner cone, 0 outside
// the outer. L: unit vector from the surface to the light. A point light
// (spot.w = -2, scale 1, include/frame.glsl) gets exactly 1.
float spotCone(PointLight light, vec3 L) {
  float t = clamp((dot(light.spot.xyz, -L) - light.spot.w) * light.attenuation.w, 0.0, 1.0);
  return t * t;
}

// LearnOpenGL's Blinn-Phong: diffuse + specular with exponent 16 scaled by the
// stored specular intensity. radiance = light colour * attenuation.
vec3 blinnPhong(vec3 N, vec3 V, vec3 L, vec3 radiance, vec3 albedo, float specular) {
  vec3 diffuse = max(dot(N, L), 0.0) * albedo * radiance;
  vec3 H = halfVector(L, V, N);
  vec3 spec = pow(max(dot(N, H), 0.0), 16.0) * specular * radiance;
  return diffuse + spec;
}

float distributionGGX(float NdotH, float roughness) {
  float a = roughness * roughness;
  float a2 = a * a;
  float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / max(PI * d * d, 1e-7);
}

float geometrySchlickGGX(float NdotX, float roughness) {
  float r = roughness + 1.0;
  float k = r * r / 8.0;
  return NdotX / (NdotX * (1.0 - k) + k);
}

vec3 fresnelSchlick(float cosTheta, vec3 F0, float F90) {
  return F0 + (F90 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

// The surface's reflectance at normal incidence (F0) and at grazing angles
// (F90), as KHR_materials_specular defines them: the dielectric values s.f0
// and s.f90 (0.04 and 1 without the extension) for dielectrics, the albedo
// and 1 for metals. F90 is written f90 + (1 - f90) metallic so that the
// default (f90 = 1) is exactly 1.
vec3 surfaceF0(Surface s) { return mix(s.f0, s.albedo, s.metallic); }
float surfaceF90(Surface s) { return s.f90 + (1.0 - s.f90) * s.metallic; }

// Cook-Torrance: GGX distribution, Smith geometry, Schlick Fresnel from F0
// to F90 (surfaceF0, surfaceF90), kD = (1 - F)(1 - metallic).
vec3 cookTorrance(vec3 N, vec3 V, vec3 L, vec3 radiance, vec3 albedo, float metallic, float roughness, vec3 F0,
                  float F90) {
  vec3 H = halfVector(L, V, N);
  float NdotL = max(dot(N, L), 0.0);
  float NdotV = max(dot(N, V), 0.0);
  float D = distributionGGX(max(dot(N, H), 0.0), roughness);
  float G = geometrySchlickGGX(NdotV, roughness) * geometrySchlickGGX(NdotL, roughness);
  vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0, F90);
  vec3 specular = D * G * F / max(4.0 * NdotV * NdotL, 0.001);
  vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
  return (kD * albedo / PI + specular) * radiance * NdotL;
}

vec3 shade(vec3 N, vec3 V, vec3 L, vec3 radiance, Surface s) {
#if defined(LIGHTING_COOK_TORRANCE)
  return cookTorrance(N, V, L, radiance, s.albedo, s.metallic, s.roughness, surfaceF0(s), surfaceF90(s));
#else
  return blinnPhong(N, V, L, radiance, s.albedo, s.specular);
#endif
}

vec3 shadePointLight(PointLight light, Surface s, vec3 V) {
  vec3 toLight = light.positionRadius.xyz - s.position;
  float d = length(toLight);
#if defined(LIGHT_RADIUS_BRANCH)
  // LearnOpenGL's per-light radius test: skip the shading maths outside the
  // light's volume (only pays off when whole warps agree).
  if (light.positionRadius.w >= 0.0 && d > light.positionRadius.w) return vec3(0.0);
#endif
  vec3 L = d > 1e-6 ? toLight / d : s.normal;
  float att = attenuate(light, d) * spotCone(light, L);
  return shade(s.normal, V, L, light.color.rgb * att, s);
}

vec3 shadeDirectionalLight(Surface s, vec3 V) {
  if (u_dirLightDir.w <= 0.0) return vec3(0.0);
  vec3 L = normalize(-u_dirLightDir.xyz);
  return shade(s.normal, V, L, u_dirLightColor.rgb, s);
}

#if defined(HAS_ENVIRONMENT)
// Image-based lighting (docs/ibl.md): the split-sum (Karis 2013) with the
// pre-filtered maps of passes/irradiance_cube, specular_cube and brdf_lut,
// and the multiple-scattering energy of Fdez-Aguera (2019), so that a white
// furnace returns 1 for metals and dielectrics at any roughness. F0 and F90
// are Cook-Torrance's (surfaceF0, surfaceF90: KHR_materials_specular, unlit):
// the split sum's scale and bias weigh F0 and F90, F0 * A + F90 * B.
layout(binding = 13) uniform samplerCube u_iblIrradiance;  // E / pi
layout(binding = 14) uniform samplerCube u_iblSpecular;   // level k: roughness k / (levels - 1)
layout(binding = 15) uniform sampler2D u_iblBrdfLut;      // (A, B) over (n.v, roughness)
uniform int u_hasEnvironment;  // 0: the scene has none (a pipeline run unadapted): the constant ambient

vec3 environmentTerm(Surface s, vec3 V) {
  vec3 N = s.normal;
  float NdotV = clamp(dot(N, V), 1e-4, 1.0);
  vec3 F0 = surfaceF0(s);
  float F90 = surfaceF90(s);
  vec2 ab = texture(u_iblBrdfLut, vec2(NdotV, s.roughness)).rg;
  vec3 Fr = max(vec3(F90 * (1.0 - s.roughness)), F0) - F0;  // Fresnel with roughness, towards F90
  vec3 FssEss = (F0 + Fr * pow(1.0 - NdotV, 5.0)) * ab.x + F90 * ab.y;
  float Ems = 1.0 - (ab.x + ab.y);
  vec3 Favg = F0 + (F90 - F0) / 21.0;
  vec3 FmsEms = Ems * FssEss * Favg / (1.0 - Ems * Favg);
  vec3 kD = s.albedo * (1.0 - FssEss - FmsEms) * (1.0 - s.metallic);
  float lod = s.roughness * float(textureQueryLevels(u_iblSpecular) - 1);
  vec3 radiance = textureLod(u_iblSpecular, reflect(-V, N), lod).rgb;
  vec3 irradiance = texture(u_iblIrradiance, N).rgb;
  return (FssEss * radiance + (FmsEms + kD) * irradiance) * s.ao;
}
#endif

// Light that is not from a light: with an environment (HAS_ENVIRONMENT) the
// image-based term, otherwise LearnOpenGL's constant ambient * albedo.
vec3 ambientTerm(Surface s, vec3 V) {
#if defined(HAS_ENVIRONMENT)
  if (u_hasEnvironment != 0) return environmentTerm(s, V);
#endif
  return u_ambient.rgb * s.albedo * s.ao;
}

// Light the surface emits (glTF emissive; unlit materials' base colour):
// added once per pixel, after the lights, before tone mapping, by whichever
// pass adds ambientTerm.
vec3 emissiveTerm(Surface s) { return s.emissive; }
