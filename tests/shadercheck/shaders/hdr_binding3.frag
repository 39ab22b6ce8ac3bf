#version 450 core
layout(location = 0) out vec4 o_color;
layout(binding = 3) uniform sampler2D u_hdr;  // the tonemap-like test pass binds its input on unit 0
void main() { o_color = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0); }
