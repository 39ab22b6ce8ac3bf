#version 450 core
// G-buffer debug views (the PBR chapter's visualisations).
#include "include/frame.glsl"
#include "include/gbuffer.glsl"
#include "include/gbuffer_read.glsl"

uniform int u_mode;  // 0 position, 1 normal_abs, 2 normal, 3 albedo, 4 specular, 5 metallic, 6 roughness, 7 depth
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  Surface s = readSurface(px);
  vec3 c = vec3(0.0);
  if (s.covered) {
    if (u_mode == 0) c = 0.5 + 0.5 * sign(s.position) * log(abs(s.position) + 1.0) / log(3.0);
    else if (u_mode == 1) c = abs(s.normal);
    else if (u_mode == 2) c = s.normal * 0.5 + 0.5;
    else if (u_mode == 3) c = s.albedo;
    else if (u_mode == 4) c = vec3(s.specular);
    else if (u_mode == 5) c = vec3(s.metallic);
    else if (u_mode == 6) c = vec3(s.roughness);
    else {
      // Linear depth: view-space distance along -Z, mapped over the near..far range.
      float z = -(u_view * vec4(s.position, 1.0)).z;
      float nearPlane = u_proj[3][2] / (u_proj[2][2] - 1.0);
      float farPlane = u_proj[3][2] / (u_proj[2][2] + 1.0);
      c = vec3(clamp((z - nearPlane) / (farPlane - nearPlane), 0.0, 1.0));
    }
  }
  outColor = vec4(c, 1.0);
}
