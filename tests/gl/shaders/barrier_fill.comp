#version 450 core
// Test shader: gradient.frag's pattern written with image stores (pixel
// (x, y), y = 0 at the bottom row).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba8, binding = 0) writeonly uniform image2D u_out;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_out)))) return;
  imageStore(u_out, p, vec4((p.x * 4) & 255, (p.y * 4) & 255, (p.x ^ p.y) & 255, 255) / 255.0);
}
