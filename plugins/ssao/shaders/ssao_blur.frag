#version 450 core
// SSAO, step 2: a box blur over the 4x4 tile of the noise rotations (size 2:
// offsets -2..1), which removes their pattern (LearnOpenGL). Edges clamp.
layout(binding = 0) uniform sampler2D u_src;
uniform int u_size;  // half width; 0 copies
layout(location = 0) out float outAo;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(u_src, 0) - 1;
  if (u_size <= 0) {
    outAo = texelFetch(u_src, clamp(px, ivec2(0), last), 0).r;
    return;
  }
  float sum = 0.0;
  for (int y = -u_size; y < u_size; ++y)
    for (int x = -u_size; x < u_size; ++x) sum += texelFetch(u_src, clamp(px + ivec2(x, y), ivec2(0), last), 0).r;
  outAo = sum / float(4 * u_size * u_size);
}
