#version 450 core
// Test shader: gradient.frag's pattern packed one uint per pixel (RGBA8,
// R in the low byte) into a storage buffer, rows bottom-up.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) writeonly buffer Pixels { uint pixels[]; };
layout(location = 0) uniform ivec2 u_size;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, u_size))) return;
  uint r = uint(p.x * 4) & 255u, g = uint(p.y * 4) & 255u, b = uint(p.x ^ p.y) & 255u;
  pixels[p.y * u_size.x + p.x] = r | (g << 8) | (b << 16) | (255u << 24);
}
