#version 450 core
layout(location = 0) out vec4 o_color;
uniform isampler2D input0;
void main() { o_color = vec4(texelFetch(input0, ivec2(gl_FragCoord.xy), 0)); }
