#version 450 core
// frame.glsl's Frame block with u_view and u_proj swapped and u_counts a vec4:
// the layout comparison of frame_block_layout_test.cpp must name all three.
layout(std140, binding = 0) uniform Frame {
  mat4 u_proj;
  mat4 u_view;
  mat4 u_viewProj;
  mat4 u_invView;
  mat4 u_invProj;
  vec4 u_cameraPos;
  vec4 u_viewport;
  vec4 u_ambient;
  vec4 u_dirLightDir;
  vec4 u_dirLightColor;
  vec4 u_counts;
  mat4 u_prevViewProj;
  mat4 u_viewProjNoJitter;
  vec4 u_jitter;
  ivec4 u_frame;
};
layout(local_size_x = 1) in;
layout(std430, binding = 1) writeonly buffer Out { vec4 o_value; };
void main() { o_value = u_cameraPos; }
