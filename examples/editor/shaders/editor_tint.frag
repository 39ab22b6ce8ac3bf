#version 450 core
// The editor's own pass (editor_pipeline.cpp): the frame times a colour.
layout(binding = 0) uniform sampler2D u_src;
uniform vec4 u_color;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_src, ivec2(gl_FragCoord.xy), 0) * u_color; }
