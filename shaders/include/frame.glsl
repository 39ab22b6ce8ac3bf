// Per-frame data shared by every scene pass (std140, binding 0), filled by the
// executor's GPU scene from the scene camera and lights. Its C++ mirror is
// FrameBlock in core/src/gl/frame_block.h: the ctest
// FrameBlockLayout.EveryMemberOfFrameGlslHasTheOffsetAndTypeOfFrameBlock fails
// when a member here and there differ in offset or type (change both).
// Each member's comment is its documentation: the Frame table in
// docs/writing-a-pass.md is generated from this block (rgraph_doc_tables; the
// ctest docs.generated_tables fails when they differ). A comment line indented
// deeper than the members continues the member above it.
layout(std140, binding = 0) uniform Frame {
  mat4 u_view;             // world -> view (the camera; glm::lookAt)
  mat4 u_proj;             // view -> clip (OpenGL clip space, depth -1..1), with this frame's jitter when the
                           // pipeline jitters
  mat4 u_viewProj;         // u_proj * u_view (jittered): what scene.vert draws with
  mat4 u_invView;          // inverse of u_view
  mat4 u_invProj;          // inverse of u_proj (jittered too, so positions rebuilt from this frame's depth are
                           // right)
  vec4 u_cameraPos;        // xyz: camera position (world)
  vec4 u_viewport;         // width, height, 1/width, 1/height (pixels)
  vec4 u_ambient;          // rgb: ambient factor applied to albedo
  vec4 u_dirLightDir;      // xyz: the direction the first directional light travels (world); w: 1 when there
                           // is one
  vec4 u_dirLightColor;    // rgb: its colour * intensity
  ivec4 u_counts;          // x: point lights
  // Motion and jitter (docs/writing-a-pass.md, "The Frame block"). u_proj,
  // u_viewProj and u_invProj above carry the jitter; these do not.
  mat4 u_prevViewProj;     // the previous frame's unjittered view-projection; equal to u_viewProjNoJitter on
                           // the first frame, after a camera cut, and without motion
  mat4 u_viewProjNoJitter; // this frame's unjittered view-projection
  vec4 u_jitter;           // xy: this block's jitter in pixels (each in -0.5..0.5); zw: the same in NDC
                           // (2 * xy / size), added to clip xy / w. 0 without jitter and in the unjittered block
  ivec4 u_frame;           // x: the executor's frame index (mod 2^31); y: jitter phases (0: off)
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
