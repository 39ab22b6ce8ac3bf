#version 450 core
// Test shader: unpacks barrier_fill_buffer.comp's buffer into an image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Pixels { uint pixels[]; };
layout(rgba8, binding = 0) writeonly uniform image2D u_out;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_out);
  if (any(greaterThanEqual(p, size))) return;
  imageStore(u_out, p, unpackUnorm4x8(pixels[p.y * size.x + p.x]));
}
