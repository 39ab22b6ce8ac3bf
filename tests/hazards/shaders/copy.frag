#version 450 core
// The source texel for texel (the hazard fixtures' reader).
layout(binding = 0) uniform sampler2D u_src;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_src, ivec2(gl_FragCoord.xy), 0); }
