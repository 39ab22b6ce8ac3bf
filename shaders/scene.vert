#version 450 core
// Scene geometry: world-space position, normal and tangent for the geometry
// and forward passes. Attributes follow rgraph::MeshVertex (gpu_scene.h).
// LAYERED: for GpuScene::drawLayered, view i of the LayerViews block draws
// into layer u_layerBase.x + i (gl_Layer from the vertex shader: one of the
// two extensions below, GpuScene::supportsLayeredDraw).
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
layout(location = 4) in vec4 a_color;  // COLOR_0, bound only where the mesh has it
layout(location = 5) in vec2 a_uv1;    // TEXCOORD_1, bound only where a texture samples it

// Per object (GpuScene's Objects buffer, one entry per primitive, rewritten
// only where something moved): this frame's model matrix, the previous
// frame's (motion vectors) and the normal matrix (a mat3 in a mat4's
// columns). u_object: this draw's entry. The names below read it.
struct SceneObject {
  mat4 model;
  mat4 prevModel;
  mat4 normalMatrix;
};
layout(std430, binding = 5) readonly buffer Objects { SceneObject u_objects[]; };
uniform int u_object;
#define u_model (u_objects[u_object].model)
#define u_normalMatrix (mat3(u_objects[u_object].normalMatrix))
#define u_prevModel (u_objects[u_object].prevModel)
// Per draw: whether the mesh has vertex colours (attribute 4 is read only
// then: a mesh without COLOR_0 is white), and its instances
// (EXT_mesh_gpu_instancing): x their count (0: not instanced, u_model alone),
// y the first one's entry in Instances.
uniform int u_hasVertexColors;
uniform ivec2 u_instanceRange;

// Per instance: its local matrix (applied before u_model) and that matrix's
// normal matrix in a mat4's columns (GpuScene::uploadInstances).
struct SceneInstance {
  mat4 model;
  mat4 normal;
};
layout(std430, binding = 7) readonly buffer Instances { SceneInstance u_instances[]; };

#if defined(HAS_VELOCITY)
// Motion vectors: this frame's and the previous frame's unjittered clip
// positions (the velocity target is uv_now - uv_prev, jitter excluded).
out vec4 vs_clipNow;
out vec4 vs_clipPrev;
#endif

out VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} vs;
out vec4 vs_color;  // COLOR_0 (white without): material.glsl multiplies the base colour by it
out vec2 vs_uv1;    // the second UV set (material_uv.glsl)

void main() {
#if defined(LAYERED)
  // GL instance k: view k % views of scene instance k / views.
  int views = max(u_layerBase.y, 1);
  int view = gl_InstanceID % views;
  int instance = gl_InstanceID / views;
#else
  int instance = gl_InstanceID;
#endif
  vec4 local = vec4(a_position, 1.0);
  vec3 normal = a_normal;
  vec3 tangent = a_tangent.xyz;
  if (u_instanceRange.x > 0) {
    SceneInstance s = u_instances[u_instanceRange.y + instance];
    local = s.model * local;
    normal = mat3(s.normal) * normal;
    tangent = mat3(s.model) * tangent;
  }
  vec4 world = u_model * local;
  vs.worldPos = world.xyz;
  vs.normal = u_normalMatrix * normal;
  vs.uv = a_uv;
  vs.tangent = vec4(mat3(u_model) * tangent, a_tangent.w);
  vs_color = u_hasVertexColors != 0 ? a_color : vec4(1.0);
  vs_uv1 = a_uv1;
#if defined(LAYERED)
  gl_Position = u_layerViewProj[view] * world;
  gl_Layer = u_layerBase.x + view;
#else
  gl_Position = u_viewProj * world;
#endif
#if defined(HAS_VELOCITY)
  vs_clipNow = u_viewProjNoJitter * world;
  vs_clipPrev = u_prevViewProj * (u_prevModel * local);
#endif
}
