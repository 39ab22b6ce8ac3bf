#version 450 core
// Test shader: a cube-map sampler on input0 (its slot needs a cube texture).
uniform samplerCube input0;
uniform vec2 u_resolution;
layout(location = 0) out vec4 o_color;

void main() {
  vec2 uv = gl_FragCoord.xy / u_resolution * 2.0 - 1.0;
  o_color = texture(input0, vec3(uv, 1.0));
}
