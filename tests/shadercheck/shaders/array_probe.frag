#version 450 core
// Test shader: a 2D-array sampler on input0 (its slot needs several layers).
uniform sampler2DArray input0;
uniform vec2 u_resolution;
layout(location = 0) out vec4 o_color;

void main() {
  o_color = texture(input0, vec3(gl_FragCoord.xy / u_resolution, 0.0));
}
