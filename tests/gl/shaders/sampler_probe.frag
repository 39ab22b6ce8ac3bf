#version 450 core
// Test shader: samples input0 at uv = pixel centre / resolution * u_color.xy
// + u_color.zw (an offset moves the lookup outside [0, 1] to test wrapping).
uniform sampler2D input0;
uniform vec2 u_resolution;
uniform vec4 u_color;
layout(location = 0) out vec4 o_color;

void main() {
  o_color = texture(input0, gl_FragCoord.xy / u_resolution * u_color.xy + u_color.zw);
}
