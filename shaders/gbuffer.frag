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

#if defined(HAS_VELOCITY)
// The velocity target comes after the layout's colour targets (the geometry
// pass declares its slot last): uv_now - uv_prev, unjittered.
#if defined(GBUFFER_LEARNOPENGL) || (defined(GBUFFER_COMPACT) && !defined(CONSTANT_MATERIAL)) || \
    (!defined(GBUFFER_COMPACT) && defined(CONSTANT_MATERIAL))
#define VELOCITY_LOCATION 3
#elif defined(GBUFFER_COMPACT)
#define VELOCITY_LOCATION 2
#else
#define VELOCITY_LOCATION 4
#endif
layout(location = VELOCITY_LOCATION) out vec2 outVelocity;
in vec4 vs_clipNow;
in vec4 vs_clipPrev;
#endif

void main() {
  float alpha;
  bool discarded;
  Surface s = materialSurface(normalize(u_cameraPos.xyz - fs.worldPos), alpha, discarded);
  if (discarded) discard;
#if defined(HAS_VELOCITY)
  outVelocity = screenVelocity(vs_clipNow, vs_clipPrev);
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
