// Per-frame data shared by every scene pass (std140, binding 0), filled by the
// executor's GPU scene from the scene camera and lights. Keep in sync with
// core/src/gl/gpu_scene.cpp (FrameBlock).
layout(std140, binding = 0) uniform Frame {
  mat4 u_view;
  mat4 u_proj;
  mat4 u_viewProj;
  mat4 u_invView;
  mat4 u_invProj;
  vec4 u_cameraPos;      // xyz world position
  vec4 u_viewport;       // width, height, 1/width, 1/height
  vec4 u_ambient;        // rgb: ambient factor applied to albedo
  vec4 u_dirLightDir;    // xyz: direction the light travels (world), w: 1 when present
  vec4 u_dirLightColor;  // rgb * intensity
  ivec4 u_counts;        // x: point lights
  // Motion and jitter (docs/writing-a-pass.md, "Frame block"). u_proj,
  // u_viewProj and u_invProj above carry the jitter; these do not.
  mat4 u_prevViewProj;     // the previous frame's unjittered view-projection (= u_viewProjNoJitter after a cut)
  mat4 u_viewProjNoJitter; // this frame's unjittered view-projection
  vec4 u_jitter;           // xy: jitter in pixels (-0.5..0.5), zw: the NDC offset added to clip xy / w
  ivec4 u_frame;           // x: frame index (mod 2^31), y: jitter phases (0: none)
};

// A point or spot light (std430, binding 0 of the lights buffer; the point
// lights first, then the spot lights). Keep in sync with core/src/gl/gpu_scene.cpp
// (GpuPointLight). A point light is a spot light whose cone is every
// direction (spot.w = -2): spotCone() (include/lighting.glsl) gives it exactly 1.
struct PointLight {
  vec4 positionRadius;   // xyz world position, w: cut-off radius (negative: no cut-off)
  vec4 color;            // rgb * intensity
  vec4 attenuation;      // constant, linear, quadratic; w: 1 / max(cos(inner) - cos(outer), 1e-3) (glTF's cone scale)
  vec4 spot;             // xyz: unit direction the cone points (world); w: cos(outer cone angle), -2 for a point light
};
