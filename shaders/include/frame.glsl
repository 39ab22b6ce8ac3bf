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
};

// A point light (std430, binding 0 of the lights buffer).
struct PointLight {
  vec4 positionRadius;   // xyz world position, w: cut-off radius (negative: no cut-off)
  vec4 color;            // rgb * intensity
  vec4 attenuation;      // constant, linear, quadratic, unused
};
