#version 450 core
// Scene geometry: world-space position, normal and tangent for the geometry
// and forward passes. Attributes follow rgraph::MeshVertex (gpu_scene.h).
// LAYERED: for GpuScene::drawLayered, instance i draws with the i-th view of
// the LayerViews block into layer u_layerBase.x + i (gl_Layer from the vertex
// shader: one of the two extensions below, GpuScene::supportsLayeredDraw).
#if defined(LAYERED)
#extension GL_ARB_shader_viewport_layer_array : enable
// The AMD one only where the compiler has it (its macro is defined): glslang,
// which validate checks with, knows only the ARB one and would warn.
#if defined(GL_AMD_vertex_shader_layer)
#extension GL_AMD_vertex_shader_layer : enable
#endif
#endif
#include "include/frame.glsl"
#if defined(LAYERED)
#include "include/layer_views.glsl"
#endif

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_tangent;

uniform mat4 u_model;
uniform mat3 u_normalMatrix;

#if defined(HAS_VELOCITY)
// Motion vectors: this frame's and the previous frame's unjittered clip
// positions (the velocity target is uv_now - uv_prev, jitter excluded).
uniform mat4 u_prevModel;
out vec4 vs_clipNow;
out vec4 vs_clipPrev;
#endif

out VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} vs;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  vs.worldPos = world.xyz;
  vs.normal = u_normalMatrix * a_normal;
  vs.uv = a_uv;
  vs.tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
#if defined(LAYERED)
  gl_Position = u_layerViewProj[gl_InstanceID] * world;
  gl_Layer = u_layerBase.x + gl_InstanceID;
#else
  gl_Position = u_viewProj * world;
#endif
#if defined(HAS_VELOCITY)
  vs_clipNow = u_viewProjNoJitter * world;
  vs_clipPrev = u_prevViewProj * (u_prevModel * vec4(a_position, 1.0));
#endif
}
