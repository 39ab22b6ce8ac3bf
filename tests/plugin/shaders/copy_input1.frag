#version 450 core
// Copies the fullscreen pass's input1 through samplers without layout(binding):
// both would read unit 0 unless the executor sets each sampler uniform to the
// unit the pass's spec names (input0 -> 0, input1 -> 1). input0 stays active.
uniform sampler2D input0;
uniform sampler2D input1;
layout(location = 0) out vec4 o_color;

void main() {
  o_color = texelFetch(input1, ivec2(gl_FragCoord.xy), 0);
  if (texelFetch(input0, ivec2(0), 0).a < 0.0) o_color = vec4(1.0);  // never: alpha is not negative
}
