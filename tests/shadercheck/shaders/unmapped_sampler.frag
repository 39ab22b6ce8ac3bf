#version 450 core
layout(location = 0) out vec4 o_color;
uniform sampler2D u_lookup;  // no input of the fullscreen pass is called this
void main() { o_color = texelFetch(u_lookup, ivec2(gl_FragCoord.xy), 0); }
