#version 450 core
layout(location = 0) out vec4 o_color;
uniform sampler2D input0;
uniform sampler2D input1;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_color = texelFetch(input0, p, 0) + texelFetch(input1, p, 0);
}
