#version 450 core
// The subresource tests' image: a known function of the pixel position (as
// gradient.frag) with u_value in blue, so that what landed in a layer or a
// level says which draw it came from. Exact in 8 bits.
layout(location = 0) out vec4 o_color;
uniform int u_value;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  o_color = vec4(float((p.x * 4) & 255), float((p.y * 4) & 255), float(u_value & 255), 255.0) / 255.0;
}
