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

#if defined(SCENE_ANIMATION)
// Skins and morph targets (GpuScene, rgraph/animation.h), compiled in only
// for scenes that have them (GpuScene::sceneDeforms: the executor adds the
// define). Joints: every skin's joint matrices at this frame, then the
// previous frame's from u_poseStride.x on; MorphWeights likewise (previous
// from u_poseStride.y). Influences: per vertex u_skin.y records of 4 joints
// (indices into the draw's skin) and weights; MorphDeltas: per vertex and
// target the deltas of the attributes in u_morph.w (bit 0 positions, 1
// normals, 2 tangents), in that order.
struct SkinInfluence {
  uvec4 joints;
  vec4 weights;
};
layout(std430, binding = 8) readonly buffer Joints { mat4 u_joints[]; };
layout(std430, binding = 9) readonly buffer MorphWeights { float u_morphWeights[]; };
layout(std430, binding = 10) readonly buffer Influences { SkinInfluence u_influences[]; };
layout(std430, binding = 11) readonly buffer MorphDeltas { vec4 u_morphDeltas[]; };
// Per draw: u_skin (first influence record, records per vertex (0: not
// skinned), first joint of the draw's skin); u_morph (first delta, target
// count (0: not morphed), first weight of the draw's node, attribute bits).
uniform ivec4 u_skin;
uniform ivec4 u_morph;
uniform ivec2 u_poseStride;

// The weighted sum of the vertex's joint matrices from joint `first` on
// (glTF: the skinned node's own transform is not applied).
mat4 skinMatrix(int first) {
  mat4 m = mat4(0.0);
  for (int s = 0; s < u_skin.y; ++s) {
    SkinInfluence f = u_influences[u_skin.x + gl_VertexID * u_skin.y + s];
    for (int k = 0; k < 4; ++k)
      if (f.weights[k] != 0.0) m += f.weights[k] * u_joints[first + int(f.joints[k])];
  }
  return m;
}

// The vertex's morph displacements with the weights from `firstWeight` on.
void morph(int firstWeight, inout vec3 position, inout vec3 normal, inout vec3 tangent) {
  int attributes = bitCount(u_morph.w);
  for (int t = 0; t < u_morph.y; ++t) {
    float w = u_morphWeights[firstWeight + t];
    if (w == 0.0) continue;
    int at = u_morph.x + (gl_VertexID * u_morph.y + t) * attributes;
    if ((u_morph.w & 1) != 0) position += w * u_morphDeltas[at++].xyz;
    if ((u_morph.w & 2) != 0) normal += w * u_morphDeltas[at++].xyz;
    if ((u_morph.w & 4) != 0) tangent += w * u_morphDeltas[at].xyz;
  }
}

// The inverse transpose of m's 3x3 (normals), m's where singular.
mat3 normalMatrixOf(mat4 m) {
  mat3 m3 = mat3(m);
  return abs(determinant(m3)) > 1e-30 ? transpose(inverse(m3)) : m3;
}
#endif

#if defined(CAPTURE_VERTICES)
// Tests only (tests/animation_gpu/deform_capture.h): every vertex drawn
// writes its world position and its clip positions now and at the previous
// frame (unjittered) at 3 * (u_object * u_captureStride + gl_VertexID).
layout(std430, binding = 12) writeonly buffer CapturedVertices { vec4 u_captured[]; };
uniform int u_captureStride;
#endif

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

// Writes the outputs of a vertex at world position `world` (and
// `prevWorld` the previous frame: motion vectors), normal and tangent in
// world space.
void emit(vec4 world, vec4 prevWorld, vec3 normal, vec3 tangent) {
#if defined(LAYERED)
  int view = gl_InstanceID % max(u_layerBase.y, 1);
#endif
  vs.worldPos = world.xyz;
  vs.normal = normal;
  vs.uv = a_uv;
  vs.tangent = vec4(tangent, a_tangent.w);
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
  vs_clipPrev = u_prevViewProj * prevWorld;
#endif
#if defined(CAPTURE_VERTICES)
  int at = 3 * (u_object * u_captureStride + gl_VertexID);
  u_captured[at] = world;
  u_captured[at + 1] = u_viewProjNoJitter * world;
  u_captured[at + 2] = u_prevViewProj * prevWorld;
#endif
}

void main() {
#if defined(LAYERED)
  // GL instance k: view k % views (emit) of scene instance k / views.
  int instance = gl_InstanceID / max(u_layerBase.y, 1);
#else
  int instance = gl_InstanceID;
#endif
  vec3 position = a_position;
  vec3 normal = a_normal;
  vec3 tangent = a_tangent.xyz;
#if defined(SCENE_ANIMATION)
  vec3 prevPosition = position;
  if (u_morph.y > 0) {
    vec3 n = normal, t = tangent;
    morph(u_morph.z + u_poseStride.y, prevPosition, n, t);
    morph(u_morph.z, position, normal, tangent);
  }
  if (u_skin.y > 0) {
    // Skinned: world space straight from the joints (no model, no instances).
    mat4 skin = skinMatrix(u_skin.z);
    vec4 world = skin * vec4(position, 1.0);
    vec4 prevWorld = skinMatrix(u_skin.z + u_poseStride.x) * vec4(prevPosition, 1.0);
    normal = normalMatrixOf(skin) * normal;
    tangent = mat3(skin) * tangent;
    emit(world, prevWorld, normal, tangent);
    return;
  }
#else
  vec3 prevPosition = position;
#endif
  vec4 local = vec4(position, 1.0);
  vec4 prevLocal = vec4(prevPosition, 1.0);
  if (u_instanceRange.x > 0) {
    SceneInstance s = u_instances[u_instanceRange.y + instance];
    local = s.model * local;
    prevLocal = s.model * prevLocal;
    normal = mat3(s.normal) * normal;
    tangent = mat3(s.model) * tangent;
  }
  emit(u_model * local, u_prevModel * prevLocal, u_normalMatrix * normal, mat3(u_model) * tangent);
}
