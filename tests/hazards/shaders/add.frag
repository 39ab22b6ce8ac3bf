#version 450 core
// Two sources added texel for texel.
layout(binding = 0) uniform sampler2D u_a;
layout(binding = 1) uniform sampler2D u_b;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_a, ivec2(gl_FragCoord.xy), 0) + texelFetch(u_b, ivec2(gl_FragCoord.xy), 0); }
