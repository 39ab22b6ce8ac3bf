#version 450 core
// Reads the fullscreen pass's input1: a config that leaves input1 unbound
// would sample texture 0 (black), which the shader checks refuse.
layout(binding = 1) uniform sampler2D input1;
layout(location = 0) out vec4 o_color;

void main() { o_color = texelFetch(input1, ivec2(gl_FragCoord.xy), 0); }
