#version 450 core
// Test shader (with scene.vert, LAYERED or not): the world position and depth
// of each fragment; with FRAME_TERMS, what the Frame block gives it instead
// (the distance to u_cameraPos, the pixel in u_viewport units, the depth), so
// a test sees which block a draw read.
#include "include/frame.glsl"

in VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} fs;

layout(location = 0) out vec4 outColor;

void main() {
#if defined(FRAME_TERMS)
  outColor = vec4(distance(u_cameraPos.xyz, fs.worldPos), gl_FragCoord.xy * u_viewport.zw, gl_FragCoord.z);
#else
  outColor = vec4(fs.worldPos, gl_FragCoord.z);
#endif
}
