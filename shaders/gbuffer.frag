#version 450 core
// Geometry pass: writes one G-buffer layout (GBUFFER_* define, see
// include/gbuffer.glsl). Output locations follow the order in which the
// geometry pass declares its slots, counting only the slots a layout binds.
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/material_uv.glsl"
#include "include/material.glsl"

#if defined(GBUFFER_COMPACT)
layout(location = 0) out vec2 outNormal;    // octahedral
layout(location = 1) out vec4 outAlbedo;    // rgb albedo, a specular
#if !defined(CONSTANT_MATERIAL)
layout(location = 2) out vec2 outMaterial;  // metallic, roughness
#endif
#elif defined(GBUFFER_LEARNOPENGL)
layout(location = 0) out vec4 outPosition;  // xyz world, w 1 where covered
layout(location = 1) out vec4 outNormal;    // xyz world, w 1 where covered
layout(location = 2) out vec4 outAlbedo;    // rgb albedo, a specular
#else  // GBUFFER_PBR, GBUFFER_FP32
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;    // rgb albedo, a specular
#if !defined(CONSTANT_MATERIAL)
layout(location = 3) out vec4 outMaterial;  // metallic, roughness, ao
#endif
#endif

// The optional targets follow the layout's own, in the table's slot order,
// then the velocity target (the geometry pass declares its slot last):
// locations count the targets bound before them.
#if defined(GBUFFER_COMPACT)
#define BASE_TARGETS 2
#else
#define BASE_TARGETS 3
#endif
#if defined(GBUFFER_LEARNOPENGL) || defined(CONSTANT_MATERIAL)
#define MATERIAL_TARGETS 0
#else
#define MATERIAL_TARGETS 1
#endif
#define EMISSIVE_LOCATION (BASE_TARGETS + MATERIAL_TARGETS)
#if defined(HAS_EMISSIVE_TARGET)
// r11g11b10f in learnopengl and compact (three components), rgba16f / rgba32f
// in pbr and fp32 (alpha unused, written 1).
#if defined(GBUFFER_COMPACT) || defined(GBUFFER_LEARNOPENGL)
layout(location = EMISSIVE_LOCATION) out vec3 outEmissive;
#define EMISSIVE_OUT(e) (e)
#else
layout(location = EMISSIVE_LOCATION) out vec4 outEmissive;
#define EMISSIVE_OUT(e) vec4(e, 1.0)
#endif
#define REFLECTANCE_LOCATION (EMISSIVE_LOCATION + 1)
#else
#define REFLECTANCE_LOCATION EMISSIVE_LOCATION
#endif
#if defined(HAS_REFLECTANCE_TARGET)
layout(location = REFLECTANCE_LOCATION) out vec4 outReflectance;  // rgb dielectric F0, a F90
#define VELOCITY_LOCATION (REFLECTANCE_LOCATION + 1)
#else
#define VELOCITY_LOCATION REFLECTANCE_LOCATION
#endif

#if defined(HAS_VELOCITY)
// uv_now - uv_prev, unjittered.
layout(location = VELOCITY_LOCATION) out vec2 outVelocity;
in vec4 vs_clipNow;
in vec4 vs_clipPrev;
#define OBJECT_ID_LOCATION (VELOCITY_LOCATION + 1)
#else
#define OBJECT_ID_LOCATION VELOCITY_LOCATION
#endif

#if defined(HAS_OBJECT_ID)
// Picking (gbuffer::objectIdTarget, rg32ui): the draw's entry in the Objects
// buffer + 1 (scene.vert's u_object, the same uniform here; 0 is the
// geometry pass's clear: nothing) and the triangle within the draw.
layout(location = OBJECT_ID_LOCATION) out uvec2 outObjectId;
uniform int u_object;
#endif

void main() {
  float alpha;
  bool discarded;
  Surface s = materialSurface(normalize(u_cameraPos.xyz - fs.worldPos), alpha, discarded);
  if (discarded) discard;
#if defined(HAS_EMISSIVE_TARGET)
  outEmissive = EMISSIVE_OUT(s.emissive);
#endif
#if defined(HAS_REFLECTANCE_TARGET)
  outReflectance = vec4(s.f0, s.f90);
#endif
#if defined(HAS_VELOCITY)
  outVelocity = screenVelocity(vs_clipNow, vs_clipPrev);
#endif
#if defined(HAS_OBJECT_ID)
  outObjectId = uvec2(uint(u_object) + 1u, uint(gl_PrimitiveID));
#endif
#if defined(GBUFFER_COMPACT)
  outNormal = encodeOctahedral(s.normal);
  outAlbedo = vec4(s.albedo, s.specular);
#if !defined(CONSTANT_MATERIAL)
  outMaterial = vec2(s.metallic, s.roughness);
#endif
#else
  outPosition = vec4(s.position, 1.0);
  outNormal = vec4(s.normal, 1.0);
  outAlbedo = vec4(s.albedo, s.specular);
#if !defined(GBUFFER_LEARNOPENGL) && !defined(CONSTANT_MATERIAL)
  outMaterial = vec4(s.metallic, s.roughness, s.ao, 1.0);
#endif
#endif
}
