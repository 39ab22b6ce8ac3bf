#version 450 core
// Test shader: a shadow sampler on input0 (its slot needs a compare mode).
uniform sampler2DShadow input0;
uniform vec2 u_resolution;
uniform float u_value;
layout(location = 0) out vec4 o_color;

void main() {
  vec2 uv = gl_FragCoord.xy / u_resolution;
  o_color = vec4(texture(input0, vec3(uv, u_value)));
}
