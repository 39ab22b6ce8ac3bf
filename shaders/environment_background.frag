#version 450 core
// passes/environment_background: the environment (level 0 of its cube)
// where nothing was drawn (depth 1): the direction through the pixel from
// the camera, by the Frame block's inverse matrices.
#include "include/frame.glsl"

layout(binding = 0) uniform samplerCube u_environment;
layout(binding = 1) uniform sampler2D u_depth;

layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (texelFetch(u_depth, p, 0).r < 1.0) discard;
  vec2 ndc = gl_FragCoord.xy * u_viewport.zw * 2.0 - 1.0;
  vec4 view = u_invProj * vec4(ndc, 1.0, 1.0);
  vec3 dir = normalize((u_invView * vec4(view.xyz / view.w, 0.0)).xyz);
  outColor = vec4(textureLod(u_environment, dir, 0.0).rgb, 1.0);
}
