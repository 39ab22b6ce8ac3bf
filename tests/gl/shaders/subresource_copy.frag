#version 450 core
// Copies texel for texel what the bound subresource holds at its level 0
// (a view's first level, or the texture's base level).
layout(binding = 0) uniform sampler2D u_src;
layout(location = 0) out vec4 o_color;

void main() { o_color = texelFetch(u_src, ivec2(gl_FragCoord.xy), 0); }
