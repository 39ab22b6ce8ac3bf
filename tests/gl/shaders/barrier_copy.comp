#version 450 core
// Test shader: copies one image into another with image loads and stores.
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba8, binding = 0) readonly uniform image2D u_src;
layout(rgba8, binding = 1) writeonly uniform image2D u_dst;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_dst)))) return;
  imageStore(u_dst, p, imageLoad(u_src, p));
}
