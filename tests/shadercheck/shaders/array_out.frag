#version 450 core
layout(location = 0) out vec4 o_targets[4];  // locations 0..3
void main() { for (int i = 0; i < 4; ++i) o_targets[i] = vec4(float(i)); }
