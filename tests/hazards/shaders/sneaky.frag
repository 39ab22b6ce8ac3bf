#version 450 core
// Planted hazard (c): samples texture unit 3, which it binds nothing to and
// declares nothing for; another pass's slot leaves a texture there.
layout(binding = 3) uniform sampler2D u_anything;
layout(location = 0) out vec4 o_color;
void main() { o_color = texelFetch(u_anything, ivec2(gl_FragCoord.xy), 0) + vec4(0.125); }
