#version 450 core
// Test shader: an ordinary 2D sampler on input0 (no compare mode allowed).
uniform sampler2D input0;
uniform vec2 u_resolution;
layout(location = 0) out vec4 o_color;

void main() {
  o_color = texture(input0, gl_FragCoord.xy / u_resolution);
}
