#version 450 core
// 1 - rgb of input0 at the same pixel (alpha kept). Applying it twice is the identity.
layout(location = 0) out vec4 o_color;
uniform sampler2D input0;

void main() {
  vec4 c = texelFetch(input0, ivec2(gl_FragCoord.xy), 0);
  o_color = vec4(1.0 - c.rgb, c.a);
}
