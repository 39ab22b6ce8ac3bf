#version 450 core
// Test shader (with scene.vert): the world position of each fragment, and the
// Frame block's jitter, so a test can see where a pixel centre landed.
#include "include/frame.glsl"

in VS_OUT {
  vec3 worldPos;
  vec3 normal;
  vec2 uv;
  vec4 tangent;
} fs;

layout(location = 0) out vec4 outWorld;
layout(location = 1) out vec4 outJitter;

void main() {
  outWorld = vec4(fs.worldPos, 1.0);
  outJitter = u_jitter;
}
