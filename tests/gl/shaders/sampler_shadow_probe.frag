#version 450 core
// Test shader: compares u_value with the depth texel at the pixel's uv.
uniform sampler2DShadow input0;
uniform vec2 u_resolution;
uniform float u_value;
layout(location = 0) out vec4 o_color;

void main() {
  o_color = vec4(texture(input0, vec3(gl_FragCoord.xy / u_resolution, u_value)));
}
