#version 450 core
// Reads one member of the Frame block (the shipped include/frame.glsl) so that
// the block is active; frame_block_layout_test.cpp compares its reflected
// layout with the C++ FrameBlock.
#include "include/frame.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 1) writeonly buffer Out { vec4 o_value; };
void main() { o_value = u_cameraPos; }
